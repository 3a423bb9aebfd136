// WriteCloudParticles: cloud particles per frame as binary little-endian PLY.

#include <mutex>
#include <utility>
#include <vector>

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
        const auto cancel = [&ctx] { ctx.checkCancelled(); };
        // The particles stream twice, with no frame-sized array: once to learn every chunk's
        // count (evaporation drops some), so each chunk's place in the file is known, then
        // with their levels and sources to be written there.
        std::mutex mutex;
        std::vector<std::pair<std::uint64_t, std::uint64_t>> chunks;
        cloud->forEachChunk(
            [&](const algo::CloudChunk& chunk) {
                const std::lock_guard<std::mutex> lock(mutex);
                chunks.emplace_back(chunk.first, chunk.count);
            },
            CloudChunkFields{}, cancel);
        const bool motion = ctx.params().getBool("motion") && cloud->hasMotion();
        util::AtomicOutput out(path);
        formats::CloudPlyChunkWriter ply(out.tempPath(), std::move(chunks),
                                         "cloud particles, frame " + std::to_string(ctx.frame()),
                                         motion);
        cloud->forEachChunk(
            [&](const algo::CloudChunk& chunk) {
                ply.write(chunk.first, chunk.count, chunk.positions, chunk.levels, chunk.sources,
                          chunk.velocities, chunk.ids);
            },
            CloudChunkFields{true, true, motion, motion}, cancel);
        ply.close();
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
        "source table); with motion, float vx, vy, vz (m/s, the particle's velocity: Eq. 10 "
        "differentiated) and uint id (the same particle has the same id on every frame, for "
        "trails and motion blur); #### in the name becomes the frame number. A frame streamed "
        "from GenerateCloud is written chunk by chunk, without a frame-sized array.",
        port("particles", "CloudParticles", "the cloud particles to write"), "cloud.####.ply");
    d.version = 2;  // each version's change: CHANGES.md, "Node versions"
    d.params.push_back(boolParam("motion", true,
                                 "write each particle's velocity and stable id (particles the "
                                 "mapper made; others have none and are written without)"));
    d.create = [] { return std::make_unique<WriteCloudParticlesNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
