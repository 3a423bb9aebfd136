// WriteParticles: vapour particles per frame as binary little-endian PLY.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/PlyWriter.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/io/IoNodes.h"
#include "nodes/io/WriterSupport.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

class WriteParticlesNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto particles = ctx.input<VapourParticlesData>("particles");
        const auto condensation = ctx.input<CondensationData>("condensation");  // optional

        std::vector<std::int32_t> state;
        if (condensation) {
            if (condensation->condensedFrame.size() != particles->size()) {
                throw InputError(ctx.nodeId(),
                                 "input 'condensation' has " +
                                     std::to_string(condensation->condensedFrame.size()) +
                                     " particles but input 'particles' has " +
                                     std::to_string(particles->size()));
            }
            state.resize(particles->size());
            for (std::size_t i = 0; i < state.size(); ++i)
                state[i] = condensation->condensed(i) ? 1 : 0;
        }

        const VapourStatics& s = *particles->statics;
        formats::PlyParticleView view;
        view.count = particles->size();
        view.x = particles->xs().data();
        view.y = particles->ys().data();
        view.z = particles->z.data();
        view.vx = particles->vxs().empty() ? nullptr : particles->vxs().data();
        view.vy = particles->vys().empty() ? nullptr : particles->vys().data();
        view.vz = particles->vz.data();
        view.temperature = particles->temperature.data();
        view.id = s.id.data();
        view.state = condensation ? state.data() : nullptr;
        view.homeCell = s.homeCell.data();

        const auto path = ctx.outputPath("file");
        util::AtomicOutput out(path);
        formats::writeParticlesPly(
            out.tempPath(), view,
            "vapour particles, frame " + std::to_string(ctx.frame()) + "; state 1 = condensed",
            [&ctx] { ctx.checkCancelled(); });
        out.commit();
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWriteParticlesNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteParticles",
        "Writes vapour particles as a binary little-endian PLY point cloud (Blender, Houdini, "
        "ParaView) under the output directory; #### in the name becomes the frame number. Each "
        "vertex has float x, y, z (m), vx, vy, vz (m/s), temperature (degC) and int id, state, "
        "home_cell; state is 1 for a condensation particle when 'condensation' is connected, "
        "else 0.",
        port("particles", "VapourParticles", "the particles to write"), "particles.####.ply");
    d.inputs.push_back(port("condensation", "Condensation",
                            "which particles have condensed (state 1); the same particles", true));
    d.version = 2;  // each version's change: CHANGES.md, "Node versions"
    d.create = [] { return std::make_unique<WriteParticlesNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
