// CloudVelocity: the velocity a fog volume's cloud moves with, from its particles' motion.

#include <memory>

#include "algo/volume/VelocityField.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/VelocityVolume.h"
#include "nodes/volume/VolumeNodes.h"

namespace cg {

namespace {

class CloudVelocityNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto particles = ctx.input<CloudParticlesData>("particles");
        const auto volume = ctx.input<FogVolumeData>("volume");
        if (!particles->hasMotion())
            throw InputError(ctx.nodeId() + "/inputs/particles",
                             "these particles carry no motion: connect GenerateCloud's particles");
        algo::VelocityFieldBuilder builder(ctx.params().getFloat("cellSize"));
        const auto cancelled = [&] { ctx.checkCancelled(); };
        particles->forEachChunk(
            [&](const algo::CloudChunk& chunk) {
                builder.add(chunk.positions, chunk.velocities, chunk.count);
            },
            CloudChunkFields{false, false, true, false}, cancelled);
        ctx.setOutput("velocity", std::make_shared<VelocityVolumeData>(
                                      builder.build(*volume->grid, cancelled)));
    }
};

}  // namespace

void registerCloudVelocityNode(Registry& registry)
{
    NodeDecl d;
    d.type = "CloudVelocity";
    d.category = "volume";
    d.doc =
        "The velocity the cloud of a fog volume moves with, for motion blur: a Vec3f grid "
        "'vel' (m/s) on the volume's transform, active exactly where the density is, for "
        "WriteVDB's velocity input. Each cloud particle moves with Eq. 10 differentiated in "
        "time: its copy's origin's velocity (the condensation particle's, or the parent "
        "particle's), plus R A / ds times the primitive particle's motion between the "
        "primitive frames around s, plus the drift past the primitive's end. Ours: the "
        "particles' velocities are averaged per cell of cellSize and interpolated between "
        "cell centres, so a voxel moves as the particles around it, and detail carved in a "
        "copy's coordinates moves with its copy; a voxel beyond every particle's cell takes "
        "the average over cells four times as large (zero beyond those). Not kept on disk.";
    d.cacheOnDisk = false;
    d.inputs = {
        port("particles", "CloudParticles", "the cloud particles the volume was made from"),
        port("volume", "FogVolume", "the volume whose active voxels get a velocity"),
    };
    d.outputs = {port("velocity", "VelocityVolume", "the grid 'vel', m/s")};
    d.params = {floatParam("cellSize", 320.0, "m",
                           "cells the particles' velocities are averaged over (value ours: "
                           "twice the figure graphs' 160 m splat radius, so every voxel a "
                           "particle reaches has that particle's cell among its corners)",
                           1.0, 100000.0)};
    d.create = [] { return std::make_unique<CloudVelocityNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
