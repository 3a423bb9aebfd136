// PrimitiveFrame: one frame of a primitive set as cloud particles, so the primitive itself can
// be voxelized, rendered and written like a mapped cloud (docs/primitive.md's pictures).

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/fluid/FluidNodes.h"

namespace cg {

namespace {

class PrimitiveFrameNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto prim = ctx.input<PrimitiveSetData>("primitive");
        const auto scale = static_cast<float>(ctx.params().getFloat("scale"));
        const Vec3 offset = ctx.params().getVec3("offset");
        // Frame s = the evaluation frame, held at the primitive's first and last frames.
        const int s = std::clamp(ctx.frame(), 0, std::max(prim->frames() - 1, 0));
        const std::uint32_t n = prim->frames() > 0 ? prim->count(s) : 0;
        std::vector<float> positions(3 * std::size_t{n});
        const float* frame = n > 0 ? prim->frame(s) : nullptr;
        for (std::size_t q = 0; q < n; ++q)
            for (int a = 0; a < 3; ++a)
                positions[3 * q + a] = static_cast<float>(offset[static_cast<std::size_t>(a)]) +
                                       scale * frame[3 * q + a];
        // Level 1, source 0: the primitive is one unmapped copy.
        ctx.setOutput("particles", std::make_shared<CloudParticlesData>(
                                       positions, std::vector<std::uint8_t>(n, 1),
                                       std::vector<std::uint32_t>(n, 0)));
    }
};

}  // namespace

void registerPrimitiveFrameNode(Registry& registry)
{
    NodeDecl d;
    d.type = "PrimitiveFrame";
    d.version = 2;  // each version's change: CHANGES.md, "Node versions"
    d.category = "fluid";
    d.frameDependent = true;
    d.doc =
        "Frame s of a primitive set as cloud particles (level 1, source 0), s = the evaluation "
        "frame held at the primitive's first and last frames, at offset + scale x P_f[i](s): "
        "the primitive alone, ready for Voxelizer, WriteCloudParticles or WritePoints.";
    d.inputs = {port("primitive", "PrimitiveSet", "the 3D cloud primitive set")};
    d.outputs = {port("particles", "CloudParticles", "the primitive's particles at frame s")};
    d.params = {floatParam("scale", 1.0, "", "metres per primitive metre", 1e-6, 1e6),
                vec3Param("offset", Vec3{0.0, 0.0, 0.0}, "m",
                          "where the cloud origin goes (x, y, z)", -1e7, 1e7)};
    d.create = [] { return std::make_unique<PrimitiveFrameNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
