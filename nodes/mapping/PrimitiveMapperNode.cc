// PrimitiveMapper: selects source particles level by level (Sec. 5.2, Eq. 12-16) and keeps
// the growing table of source records; cloud particles come from GenerateCloud.

#include <cmath>
#include <string>

#include <spdlog/spdlog.h>

#include "core/CoreData.h"
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

algo::MappingSettings settingsFrom(const CookContext& ctx, std::size_t primitives)
{
    const ParamSet& p = ctx.params();
    algo::MappingSettings s;
    s.maxLevel = static_cast<int>(p.getInt("maxLevel"));
    s.selectionRatio = p.getFloatList("selectionRatio");
    s.firstStart = static_cast<int>(p.getInt("firstStart"));
    s.levelDelay = static_cast<int>(p.getInt("levelDelay"));
    s.windowLength.clear();  // the graph's list replaces the default, it does not extend it
    for (std::int64_t w : p.getIntList("windowLength"))
        s.windowLength.push_back(static_cast<int>(w));
    s.scaleCoefficient = p.getFloat("scaleCoefficient");
    s.speedCoefficient = p.getFloat("speedCoefficient");
    s.metresPerPrimitiveMetre = p.getFloat("metresPerPrimitiveMetre");
    s.timeStep = ctx.timeStep();
    s.seed = static_cast<std::uint64_t>(p.getInt("seed"));
    s.maxSources = static_cast<std::uint64_t>(p.getInt("maxSources"));
    s.particlesPerCopy = static_cast<std::uint32_t>(p.getInt("particlesPerCopy"));
    s.parentRule = p.getString("parentRule") == "particle" ? algo::ParentRule::PerParticle
                                                           : algo::ParentRule::PerSource;
    s.pastLastFrame = p.getString("pastLastFrame") == "hold" ? algo::PastLastFrame::Hold
                                                             : algo::PastLastFrame::Drift;
    const std::string& origin = p.getString("level1Origin");
    s.level1Origin = origin == "condensationLevel" ? algo::Level1Origin::CondensationLevel
                     : origin == "trail"           ? algo::Level1Origin::Trail
                                                   : algo::Level1Origin::Particle;
    s.trailRiseSpeed = p.getFloat("trailRiseSpeed");
    s.cloudTop = p.getFloat("cloudTop");
    s.cloudTopRule = p.getString("cloudTopRule") == "spread" ? algo::CloudTopRule::Spread
                                                             : algo::CloudTopRule::Shrink;
    s.primitiveCount = static_cast<std::uint32_t>(primitives);
    return s;
}

/// Level-1 draws the cloud top refused: condensation particles taken without a record.
std::size_t refusedLevelOne(const algo::SourceTable& t)
{
    std::size_t taken = 0, records = 0;
    for (std::uint8_t v : t.condensationTaken) taken += v;
    for (const algo::Source& src : t.sources) records += src.level == 1;
    return taken - records;
}

/// Says so, once, when the cloud top refuses the first copies and lets none through: the
/// graph then makes no cloud, which would otherwise look like a bug.
void warnIfTheCapLeavesNoRoom(const algo::SourceTable& table, const CloudSourcesData* previous,
                              const algo::MappingSettings& s, const std::string& node)
{
    if (s.cloudTop <= 0.0 || refusedLevelOne(table) == 0) return;
    if (previous && refusedLevelOne(previous->table) > 0) return;  // said already
    for (const algo::Source& src : table.sources)
        if (src.level == 1) return;
    spdlog::warn(
        "{}: cloudTop {:.0f} m refused every first copy: their origins stand too "
        "close under it (or above it) for a tenth of their height; no cloud forms "
        "until cloudTop is raised",
        node, s.cloudTop);
}

class PrimitiveMapperNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto condensation = ctx.input<CondensationData>("condensation");
        const auto map = ctx.input<Map2DData>("map");
        const PrimitiveInputs primitives = primitiveInputs(ctx);
        const auto previous = ctx.previous<CloudSourcesData>("sources");
        const algo::MappingSettings settings = settingsFrom(ctx, primitives.size());
        // The previous table may come from a disk cache: it must index these inputs.
        if (previous) checkSourcesFit(previous->table, settings, *condensation, primitives);
        const PrimitiveLibraryHolder prim(primitives);
        algo::SourceTable table = algo::stepSources(
            previous ? previous->table : algo::SourceTable{}, ctx.frame(), condensation->firstFrame,
            condensationView(*condensation), mapView(*map), prim.library, settings);

        warnIfTheCapLeavesNoRoom(table, previous.get(), settings, ctx.nodeId());
        const auto counts = algo::cloudCounts(table, ctx.frame(), prim.library, settings);
        std::vector<std::int64_t> perLevel(counts.begin(), counts.end());
        std::int64_t total = 0;
        for (auto c : perLevel) total += c;
        ctx.setOutput("cloudCount", std::make_shared<IntData>(total));
        std::string text = "frame " + std::to_string(ctx.frame()) + ":";
        for (std::size_t l = 0; l < perLevel.size(); ++l)
            text += " L" + std::to_string(l + 1) + "=" + std::to_string(perLevel[l]);
        text += " total=" + std::to_string(total) +
                " sources=" + std::to_string(table.sources.size()) +
                " Lmax=" + std::to_string(table.topLevel) + "\n";
        ctx.setOutput("summary", std::make_shared<TextData>(text));
        ctx.setOutput("sources", std::make_shared<CloudSourcesData>(std::move(table), settings));
    }
};

}  // namespace

void registerPrimitiveMapperNode(Registry& registry)
{
    NodeDecl d;
    d.type = "PrimitiveMapper";
    d.version = 8;  // each version's change: CHANGES.md, "Node versions"
    d.category = "mapping";
    d.doc =
        "The recursive mapping of Sec. 5.2 (pseudocode lines 15-28). Each frame t, every active "
        "level L <= L_max whose window [t_s[L], t_e[L]] holds t selects new source particles so "
        "that G[L](t) = floor(M[L] x candidates) (Eq. 14): condensation particles for L = 1, "
        "cloud particles of level L-1 for L >= 2 (Eq. 12, 15), at random from a counter-based "
        "generator keyed by (seed, level, frame, index), without replacement: a candidate "
        "becomes a source at most once. Eq. 15 as the paper writes it (parentRule 'source'): a "
        "level L-1 source uniformly among those with particles, then one of its particles "
        "uniformly; a taken pair is drawn again. Each source records its parent, t0 = t, A = 1 + "
        "A0 fNoise and "
        "R = R0 fNoise with fNoise read under the source (Eq. 16). t_s[1] is the first "
        "condensation frame unless firstStart is set; t_s[L] = t_s[L-1] + chi; t_e[L] = t_s[L] "
        "+ windowLength[L]. L_max starts at 1 and grows by one once the top level has cloud "
        "particles (lines 26-27), up to maxLevel. Only this table is kept: GenerateCloud makes "
        "the cloud particles of a frame on demand. A simulation: each frame extends the "
        "previous frame's table.";
    d.simulation = true;
    d.readsTimeStep = true;
    d.inputs = {
        port("condensation", "Condensation",
             "the condensation particles at this frame (N_v(t), P_v)"),
        port("map", "Map2D", "the density map fNoise of Eq. 16 (the same map as Eq. 3-4)"),
    };
    for (PortDecl& p : primitivePorts()) d.inputs.push_back(std::move(p));
    d.outputs = {port("sources", "CloudSources", "the table of source records at this frame"),
                 port("cloudCount", "Int", "cloud particles of all levels at this frame (Eq. 13)"),
                 port("summary", "Text", "\"frame t: L1=N_c[1] ... total= sources= Lmax=\"")};
    using L = MappingLimits;  // the ranges a stored source table is checked against
    ParamDecl ratios;
    ratios.name = "selectionRatio";
    ratios.type = ParamType::FloatList;
    ratios.defaultValue = std::vector<double>{0.2};
    ratios.min = 0.0;
    ratios.max = 1.0;
    ratios.minSize = 1;
    ratios.maxSize = L::kMaxListSize;
    ratios.doc = "M[L] of Eq. 14, per level; the last value repeats (paper: 0.2 in Fig. 6)";
    ParamDecl windows;
    windows.name = "windowLength";
    windows.type = ParamType::IntList;
    windows.defaultValue = std::vector<std::int64_t>{100, 60};
    windows.min = 0.0;
    windows.max = static_cast<double>(L::kMaxFrames);
    windows.minSize = 1;
    windows.maxSize = L::kMaxListSize;
    windows.units = "frames";
    windows.doc =
        "t_e[L] - t_s[L], per level; the last value repeats (paper, Fig. 6: 100 for "
        "L = 1, 60 after)";
    d.params = {
        intParam("maxLevel", 5, "", "cap on L_max, the highest recursive level (paper: 4 and 5)", 1,
                 kMaxCloudLevel),
        ratios,
        intParam("firstStart", -1, "frame", "t_s[1]; -1 takes the first condensation frame", -1,
                 L::kMaxFrames),
        intParam("levelDelay", 50, "frames", "chi: t_s[L] = t_s[L-1] + chi (paper, Fig. 6: 50)", 0,
                 L::kMaxFrames),
        windows,
        floatParam("scaleCoefficient", 1.5, "", "R0 of Eq. 16: R = R0 fNoise (paper: 1.5)", 0,
                   L::kMaxCoefficient),
        floatParam("speedCoefficient", 2.0, "", "A0 of Eq. 16: A = 1 + A0 fNoise (paper: 2.0)", 0,
                   L::kMaxCoefficient),
        floatParam("metresPerPrimitiveMetre", 1.0, "m/m",
                   "global scale of every mapped primitive copy (value ours)", L::kMinMetres,
                   L::kMaxMetres),
        intParam("seed", 0, "", "keys the random selection", 0),
        intParam("maxSources", 1 << 24, "sources",
                 "selection stops at this many sources, a memory guard (value ours)", 1,
                 L::kMaxSources),
        intParam("particlesPerCopy", 0, "particles",
                 "K (ours): each copy carries about K of the primitive's particles, ids o_j, "
                 "o_j + k, ... (k = ceil(N_f(last) / K), phase o_j drawn per source, so copies "
                 "differ); keeps deep recursions near the paper's counts; 0 = all (the paper)",
                 0, L::kMaxParticlesPerCopy),
        stringParam("parentRule", "source",
                    "Eq. 15's draw of a level L >= 2 parent: 'source' (the paper: a source "
                    "uniformly, then a particle of it uniformly) or 'particle' (ours: uniformly "
                    "over all level L-1 particles, which favours big parents; a taken draw "
                    "probes forward to the next free particle)",
                    {"source", "particle"}),
        stringParam("pastLastFrame", "drift",
                    "ours: what a copy does past the primitive's last frame: 'drift' keeps its "
                    "last shape and moves on as a whole with the primitive's mean motion over "
                    "its last 10 frames, so grown turrets keep rising to the end of the "
                    "animation; 'hold' freezes it",
                    {"drift", "hold"}),
        stringParam("level1Origin", "particle",
                    "where a level 1 copy stands: 'particle' (the paper: on its condensation "
                    "particle, which keeps rising) or 'condensationLevel' (ours: below it, at the "
                    "height where it condensed, so the copies' bases line up on the condensation "
                    "level and the cloud has a flat base) or 'trail' (ours: where its particle "
                    "was when the copy was selected, and there it stays, if the particle rose at "
                    "least trailRiseSpeed then: the rising air leaves its copies behind, so a "
                    "deep updraft's stem is cloud at every height the air passed (with "
                    "Atmosphere windFrame 'storm'); a copy selected on a particle that stopped "
                    "rising rides it, so the anvil spreads with the outflow)",
                    {"particle", "condensationLevel", "trail"}),
        floatParam("trailRiseSpeed", 3.0, "m/s",
                   "level1Origin 'trail': the vertical speed from which a particle lays its copy "
                   "rather than carrying it (value ours: updrafts rise at 5-20 m/s, a tower's "
                   "top settles around its equilibrium level at a few m/s)",
                   0.0, L::kMaxTrailRiseSpeed),
        floatParam("cloudTop", 0.0, "m",
                   "ours: the height above sea level no copy rises past, 0 = none (the paper). "
                   "A copy whose origin ends up at z gets R = min(R0 fNoise, (cloudTop - z) / "
                   "top), top the primitive's highest point (its drift's rise included); one "
                   "that would keep less than a tenth of its R is not made. Set it to the "
                   "sounding's equilibrium level (`cloudgraph sounding` prints it), a few "
                   "hundred metres above for the thermals' overshoot: fair-weather cumulus stop "
                   "there, under the inversion, instead of growing as deep as the primitive",
                   0.0, 30000.0),
        stringParam("cloudTopRule", "shrink",
                    "ours: what a copy that would rise past cloudTop becomes: 'shrink' (R made "
                    "smaller, the copy keeps its shape) or 'spread' (R kept, the copy made as "
                    "much flatter as it must and wider by 1 / sqrt of that, keeping its volume: "
                    "air spreading under an inversion or the tropopause, an anvil's way)",
                    {"shrink", "spread"}),
    };
    d.create = [] { return std::make_unique<PrimitiveMapperNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
