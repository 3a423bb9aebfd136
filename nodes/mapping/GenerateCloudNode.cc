// GenerateCloud: the cloud particles of one frame, made on demand from the source table
// (Eq. 10-12).

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include <tbb/enumerable_thread_specific.h>

#include "algo/mapping/Dissipation.h"
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
                   int frame, bool evaporateBelowBase,
                   std::optional<algo::DissipationSettings> dissipation)
        : mSources(std::move(sources)),
          mCondensation(std::move(condensation)),
          mPrimitives(std::move(primitives)),
          mPrim(mPrimitives),
          mCond(condensationView(*mCondensation)),
          mFrame(frame)
    {
        if (evaporateBelowBase) mBase = algo::condensationLevel(mCond);
        if (dissipation) mDissipation = dissipationFrame(*dissipation);
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
        // Dissipation reads each particle's source, copy origin and id.
        o.sources = fields.sources || mDissipation;
        o.velocities = fields.velocities;
        o.ids = fields.ids || mDissipation;
        o.checkCancelled = checkCancelled;
        if (!mBase && !mDissipation) {
            algo::forEachCloudChunk(mSources->table, mFrame, mCond, mPrim.library,
                                    mSources->settings, consume, o);
            return;
        }
        // Each chunk handed on without its particles under the base or evaporated.
        struct Kept {
            algo::KeptParticles above, surviving;
        };
        tbb::enumerable_thread_specific<Kept> perThread;
        algo::forEachCloudChunk(
            mSources->table, mFrame, mCond, mPrim.library, mSources->settings,
            [&](const algo::CloudChunk& chunk) {
                Kept& kept = perThread.local();
                algo::CloudChunk c = mBase ? algo::chunkAbove(chunk, *mBase, kept.above) : chunk;
                if (mDissipation) c = algo::chunkSurviving(c, *mDissipation, kept.surviving);
                consume(c);
            },
            o);
    }

    algo::CloudParticleArrays materialise(
        const std::function<void()>& checkCancelled) const override
    {
        if (mDissipation) return materialiseFromChunks(checkCancelled);
        auto arrays = algo::generateCloudParticles(mSources->table, mFrame, mCond, mPrim.library,
                                                   mSources->settings, checkCancelled);
        if (mBase) algo::dropCloudParticlesBelow(arrays, *mBase);
        return arrays;
    }

    bool hasMotion() const override { return true; }

private:
    algo::DissipationFrame dissipationFrame(const algo::DissipationSettings& d) const
    {
        algo::DissipationFrame f;
        f.decay = algo::cloudDecay(mSources->table, mFrame, mPrim.library, mSources->settings, d);
        for (const algo::PrimitiveView& p : mPrim.library.views)
            f.extents.push_back(algo::primitiveExtent(p));
        f.table = &mSources->table;
        f.library = &mPrim.library;
        f.settings = &mSources->settings;
        f.dissipation = d;
        f.frame = mFrame;
        return f;
    }

    /// The frame's arrays from the filtered chunks, in particle order.
    algo::CloudParticleArrays materialiseFromChunks(
        const std::function<void()>& checkCancelled) const
    {
        std::map<std::uint64_t, algo::KeptParticles> chunks;  // by first particle
        std::vector<float> copyOrigins;                       // the same in every chunk
        std::mutex mutex;
        forEachChunk(
            [&](const algo::CloudChunk& c) {
                algo::KeptParticles k;
                k.positions.assign(c.positions, c.positions + 3 * c.count);
                k.levels.assign(c.levels, c.levels + c.count);
                k.sources.assign(c.sources, c.sources + c.count);
                const std::lock_guard<std::mutex> lock(mutex);
                if (copyOrigins.empty())
                    copyOrigins.assign(c.copyOrigins, c.copyOrigins + 3 * c.copyCount);
                chunks.emplace(c.first, std::move(k));
            },
            CloudChunkFields{true, true}, checkCancelled);
        std::size_t n = 0;
        for (const auto& [first, k] : chunks) n += k.levels.size();
        algo::CloudParticleArrays out{
            algo::UninitArray<float>(3 * n), algo::UninitArray<std::uint8_t>(n),
            algo::UninitArray<std::uint32_t>(n), algo::UninitArray<float>(copyOrigins)};
        std::size_t at = 0;
        for (const auto& [first, k] : chunks) {
            std::copy(k.positions.begin(), k.positions.end(), out.positions.data() + 3 * at);
            std::copy(k.levels.begin(), k.levels.end(), out.levels.data() + at);
            std::copy(k.sources.begin(), k.sources.end(), out.sources.data() + at);
            at += k.levels.size();
        }
        return out;
    }

    std::shared_ptr<const CloudSourcesData> mSources;
    std::shared_ptr<const CondensationData> mCondensation;
    PrimitiveInputs mPrimitives;
    PrimitiveLibraryHolder mPrim;
    algo::CondensationView mCond;  ///< views into *mCondensation
    int mFrame;
    std::optional<float> mBase;  ///< evaporation: particles under it are dropped
    std::optional<algo::DissipationFrame> mDissipation;  ///< clouds that evaporate
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
        std::optional<algo::DissipationSettings> dissipation;
        if (ctx.params().getBool("dissipate")) {
            dissipation.emplace();
            dissipation->hold = ctx.params().getFloat("hold");
            dissipation->decayTime = ctx.params().getFloat("decayTime");
            dissipation->anvilBase = ctx.params().getFloat("anvilBase");
            dissipation->anvilLife = ctx.params().getFloat("anvilLife");
        }
        auto cloud = std::make_shared<GeneratedCloud>(
            sources, condensation, primitives, ctx.frame(),
            ctx.params().getBool("evaporateBelowBase"), dissipation);
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
    d.version = 4;  // each version's change: CHANGES.md, "Node versions"
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
    d.params = {
        intParam("maxCloudParticles", 100000000, "particles",
                 "refuse a frame with more cloud particles than this, before allocating "
                 "(17 bytes each; value ours)",
                 1, 4e9),
        boolParam("evaporateBelowBase", false,
                  "ours: drop the cloud particles under the condensation level, the "
                  "lowest height at which a condensation particle condensed, as real "
                  "cloud droplets evaporate below the base; off keeps every particle "
                  "(the paper)"),
        boolParam("dissipate", false,
                  "ours: clouds evaporate once their thermal stops feeding them (their "
                  "level 1 copy's primitive has played to its end), from the edges "
                  "inward, hold seconds later, over decayTime R / R0; off keeps every "
                  "cloud forever (the paper). docs/mapper.md, 'Clouds that dissipate'"),
        floatParam("hold", 120.0, "s",
                   "ours: time between the end of a cloud's growth and its decay", 0.0, 1e6),
        floatParam("decayTime", 600.0, "s",
                   "ours: time a cloud of the largest scale (R = R0, the mapper's "
                   "scaleCoefficient) takes to evaporate; smaller clouds take "
                   "proportionally less (small cumulus live minutes, large ones tens "
                   "of minutes)",
                   0.0, 1e6),
        floatParam("anvilBase", 0.0, "m",
                   "ours: copies whose origin lies at or above this height (the anvil's "
                   "glaciated outflow) take anvilLife times longer to evaporate, as anvils "
                   "outlive their storms as cirrus; 0: none",
                   0.0, 1e5),
        floatParam("anvilLife", 4.0, "",
                   "ours: how many times longer the anvil's copies take to evaporate", 1.0, 1e3)};
    d.create = [] { return std::make_unique<GenerateCloudNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
