// WriteCloudParticles: cloud particles per frame as binary little-endian PLY.

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/CloudPly.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/mapping/MappingNodes.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

class WriteCloudParticlesNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto cloud = ctx.input<CloudParticlesData>("particles");
        const auto path = ctx.outputPath("file");
        util::AtomicOutput out(path);
        const auto& a = cloud->arrays([&ctx] { ctx.checkCancelled(); });  // a stream materialises here
        formats::writeCloudPly(out.tempPath(), a.levels.size(), a.positions.data(), a.levels.data(),
                               a.sources.data(),
                               "cloud particles, frame " + std::to_string(ctx.frame()),
                               [&ctx] { ctx.checkCancelled(); });
        out.commit();
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWriteCloudParticlesNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteCloudParticles",
        "Writes cloud particles as a binary little-endian PLY point cloud (Blender, Houdini, "
        "ParaView): float x, y, z (m), uchar level (L), uint source (index in the mapper's "
        "source table); #### in the name becomes the frame number.",
        port("particles", "CloudParticles", "the cloud particles to write"), "cloud.####.ply");
    d.create = [] { return std::make_unique<WriteCloudParticlesNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
