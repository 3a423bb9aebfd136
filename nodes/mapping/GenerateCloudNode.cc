// GenerateCloud: the cloud particles of one frame, made on demand from the source table
// (Eq. 10-12).

#include <memory>
#include <optional>
#include <utility>

#include <tbb/enumerable_thread_specific.h>

#include "algo/mapping/Evaporation.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/CloudSources.h"
#include "nodes/mapping/MappingNodes.h"
#include "nodes/mapping/MappingViews.h"
#include "nodes/mapping/PrimitivePorts.h"

namespace cg {

namespace {

/// A frame's cloud particles made on demand from the source table: chunk by chunk for
/// consumers that stream, whole for those that read arrays.
class GeneratedCloud final : public CloudParticleStream {
public:
    GeneratedCloud(std::shared_ptr<const CloudSourcesData> sources,
                   std::shared_ptr<const CondensationData> condensation, PrimitiveInputs primitives,
                   int frame, bool evaporateBelowBase)
        : mSources(std::move(sources)),
          mCondensation(std::move(condensation)),
          mPrimitives(std::move(primitives)),
          mPrim(mPrimitives),
          mCond(condensationView(*mCondensation)),
          mFrame(frame)
    {
        if (evaporateBelowBase) mBase = algo::condensationLevel(mCond);
    }

    /// How many particles the frame has before evaporation, without generating them.
    std::uint64_t particleCount() const
    {
        std::uint64_t total = 0;
        for (auto c : algo::cloudCounts(mSources->table, mFrame, mPrim.library, mSources->settings))
            total += c;
        return total;
    }

    void forEachChunk(const std::function<void(const algo::CloudChunk&)>& consume,
                      CloudChunkFields fields,
                      const std::function<void()>& checkCancelled) const override
    {
        algo::CloudChunkOptions o;
        o.levels = fields.levels;
        o.sources = fields.sources;
        o.velocities = fields.velocities;
        o.ids = fields.ids;
        o.checkCancelled = checkCancelled;
        if (!mBase) {
            algo::forEachCloudChunk(mSources->table, mFrame, mCond, mPrim.library,
                                    mSources->settings, consume, o);
            return;
        }
        // Evaporation: each chunk handed on without its particles under the base.
        tbb::enumerable_thread_specific<algo::KeptParticles> perThread;
        const float base = *mBase;
        algo::forEachCloudChunk(
            mSources->table, mFrame, mCond, mPrim.library, mSources->settings,
            [&](const algo::CloudChunk& chunk) {
                consume(algo::chunkAbove(chunk, base, perThread.local()));
            },
            o);
    }

    algo::CloudParticleArrays materialise(
        const std::function<void()>& checkCancelled) const override
    {
        auto arrays = algo::generateCloudParticles(mSources->table, mFrame, mCond, mPrim.library,
                                                   mSources->settings, checkCancelled);
        if (mBase) algo::dropCloudParticlesBelow(arrays, *mBase);
        return arrays;
    }

    bool hasMotion() const override { return true; }

private:
    std::shared_ptr<const CloudSourcesData> mSources;
    std::shared_ptr<const CondensationData> mCondensation;
    PrimitiveInputs mPrimitives;
    PrimitiveLibraryHolder mPrim;
    algo::CondensationView mCond;  ///< views into *mCondensation
    int mFrame;
    std::optional<float> mBase;  ///< evaporation: particles under it are dropped
};

class GenerateCloudNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto sources = ctx.input<CloudSourcesData>("sources");
        const auto condensation = ctx.input<CondensationData>("condensation");
        const PrimitiveInputs primitives = primitiveInputs(ctx);
        // A table read from a disk cache must index these inputs before anything reads them.
        checkSourcesFit(sources->table, sources->settings, *condensation, primitives);
        auto cloud =
            std::make_shared<GeneratedCloud>(sources, condensation, primitives, ctx.frame(),
                                             ctx.params().getBool("evaporateBelowBase"));
        const std::uint64_t total = cloud->particleCount();
        const auto limit = static_cast<std::uint64_t>(ctx.params().getInt("maxCloudParticles"));
        if (total > limit) {
            throw InputError(ctx.nodeId(),
                             "frame " + std::to_string(ctx.frame()) + " has " +
                                 std::to_string(total) +
                                 " cloud particles, over parameter maxCloudParticles = " +
                                 std::to_string(limit));
        }
        ctx.setOutput("particles", std::make_shared<CloudParticlesData>(std::move(cloud)));
    }
};

}  // namespace

void registerGenerateCloudNode(Registry& registry)
{
    NodeDecl d;
    d.type = "GenerateCloud";
    d.version = 3;  // each version's change: CHANGES.md, "Node versions"
    d.category = "mapping";
    // A frame's particles take longer to store and read back than to generate (and would
    // keep every frame's particles on disk, which the mapper's memory model rules out).
    // Kept in memory they evict everything else and cost fresh pages every frame.
    d.cacheOnDisk = false;
    d.cacheInMemory = false;
    d.doc =
        "The cloud particles of this frame, generated from PrimitiveMapper's source table: "
        "particle (L, j, i) is at P_s[L, j](t) + scale R[L, j] P_f[i](s), s = A[L, j] "
        "(t - t0[L, j]) dt / ds (Eq. 10-11), with P_s the condensation particle (L = 1) or "
        "the parent cloud particle (L >= 2, Eq. 12). P_f at a fractional s is interpolated "
        "between primitive frames; past the last frame the copy keeps its last shape and drifts "
        "on or holds (PrimitiveMapper's pastLastFrame). Particles are "
        "in source-table order, with their level and source index; the result does not "
        "depend on the thread count. Nothing is kept between frames, and nothing frame-sized is "
        "made for a consumer that takes the particles in chunks (the Voxelizer with the "
        "gaussian kernel): they are generated as it reads them. With evaporateBelowBase "
        "(ours), particles under the condensation level are dropped.";
    d.inputs = {
        port("sources", "CloudSources", "the source table at this frame"),
        port("condensation", "Condensation", "the condensation particles at this frame"),
    };
    for (PortDecl& p : primitivePorts()) d.inputs.push_back(std::move(p));
    d.outputs = {port("particles", "CloudParticles", "the cloud particles of this frame")};
    d.params = {intParam("maxCloudParticles", 100000000, "particles",
                         "refuse a frame with more cloud particles than this, before allocating "
                         "(17 bytes each; value ours)",
                         1, 4e9),
                boolParam("evaporateBelowBase", false,
                          "ours: drop the cloud particles under the condensation level, the "
                          "lowest height at which a condensation particle condensed, as real "
                          "cloud droplets evaporate below the base; off keeps every particle "
                          "(the paper)")};
    d.create = [] { return std::make_unique<GenerateCloudNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
