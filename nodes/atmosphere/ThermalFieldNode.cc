// ThermalField: a cumulus field's thermals with power-law sizes, as a density map (ours;
// algo/atmosphere/ThermalField.h).

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "algo/atmosphere/ThermalField.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/Map2D.h"

namespace cg {

namespace {

algo::ThermalFieldSettings settingsFrom(const ParamSet& p)
{
    algo::ThermalFieldSettings s;
    s.nx = static_cast<int>(p.getInt("width"));
    s.ny = static_cast<int>(p.getInt("height"));
    s.cellSize = p.getFloat("cellSize");
    s.cover = p.getFloat("cover");
    s.smallest = p.getFloat("smallestCloud");
    s.largest = p.getFloat("largestCloud");
    s.exponent = p.getFloat("exponent");
    s.gap = p.getFloat("gap");
    s.fullScaleCloud = p.getFloat("fullScaleCloud");
    s.seed = static_cast<std::uint64_t>(p.getInt("seed"));
    return s;
}

/// One line a user reads: how many thermals, how big, how many found no room.
std::string summaryOf(const algo::ThermalField& f)
{
    double largest = 0.0, smallest = 0.0;
    if (!f.thermals.empty()) {
        largest = f.thermals.front().diameter;
        smallest = f.thermals.back().diameter;
    }
    return std::to_string(f.thermals.size()) + " thermals, " +
           std::to_string(static_cast<long long>(smallest)) + "-" +
           std::to_string(static_cast<long long>(largest)) + " m across; " +
           std::to_string(f.leftOut) + " found no room";
}

/// The share of the map's cells where a cloud stands (density >= 0.5).
double coverOf(const std::vector<float>& map)
{
    std::size_t cloudy = 0;
    for (float v : map) cloudy += v >= 0.5f;
    return map.empty() ? 0.0 : static_cast<double>(cloudy) / static_cast<double>(map.size());
}

/// The parameter an unusable setting comes from.
const char* paramOf(algo::ThermalFieldError::Setting setting)
{
    using Setting = algo::ThermalFieldError::Setting;
    switch (setting) {
        case Setting::Map:
            return "width";
        case Setting::Sizes:
            return "smallestCloud";
        case Setting::Exponent:
            return "exponent";
        case Setting::Cover:
            return "cover";
        case Setting::Gap:
            return "gap";
        case Setting::FullScale:
            return "fullScaleCloud";
    }
    return "width";
}

class ThermalFieldNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const algo::ThermalFieldSettings s = settingsFrom(ctx.params());
        const algo::ThermalField field = algo::placeThermals(s);
        ctx.checkCancelled();
        std::vector<float> map = algo::thermalMap(s, field);
        if (field.leftOut * 100 > field.thermals.size() + field.leftOut)
            spdlog::warn(
                "{}: {} of {} thermals found no room: the clouds cover {:.2f} of the "
                "ground, not {:.2f} (lower cover or gap)",
                ctx.nodeId(), field.leftOut, field.thermals.size() + field.leftOut, coverOf(map),
                s.cover);
        ctx.setOutput("map", std::make_shared<Map2DData>(s.nx, s.ny, s.cellSize, std::move(map)));
        ctx.setOutput("starts", std::make_shared<Map2DData>(s.nx, s.ny, s.cellSize,
                                                            algo::thermalStartMap(s, field)));
        ctx.setOutput("scale", std::make_shared<Map2DData>(s.nx, s.ny, s.cellSize,
                                                           algo::thermalScaleMap(s, field)));
        ctx.setOutput("summary", std::make_shared<TextData>(summaryOf(field)));
    }
};

}  // namespace

void registerThermalFieldNode(Registry& registry)
{
    NodeDecl d;
    d.type = "ThermalField";
    d.version = 3;  // each version's change: CHANGES.md, "Node versions"
    d.category = "atmosphere";
    d.doc =
        "Ours, in place of the paper's single 1/f^beta map for a cumulus field: thermals whose "
        "cloud diameters l follow a power-law number density n(l) ~ l^exponent between "
        "smallestCloud and largestCloud (the scale break near the boundary layer's depth), "
        "placed at random without overlapping (largest first; gap keeps neighbours apart) "
        "until their clouds cover `cover` of the ground (above about 0.3 the ground fills up: the "
        "log says the cover reached), as a density map: 1 within half a "
        "thermal's disk radius, smoothly 0 at its radius, the 0.5 contour l across. Wire it "
        "to the VapourEmitter's and the PrimitiveMapper's map. Defaults from the literature: "
        "exponent -1.7 (shallow cumulus in large-eddy simulations, Neggers et al. 2003; "
        "satellite studies give -1.7 to -2.5), cover 0.25, clouds 200 m to 2 km. Every draw "
        "is counter-based on the seed: the same settings give the same field. See "
        "docs/atmosphere.md.";
    d.outputs = {
        port("map", "Map2D", "the thermals' density in [0, 1], row iy = 0 at y = 0"),
        port("starts", "Map2D",
             "each thermal's own uniform draw in [0, 1) over its disk, 0 elsewhere: wired to "
             "the VapourEmitter's startDelay, thermals start one by one over startDelayMax"),
        port("scale", "Map2D",
             "ours: min(1, l / fullScaleCloud) of the nearest thermal (its own over its disk): "
             "wired to the PrimitiveMapper's map, a thermal smaller than one copy makes a "
             "smaller copy (Eq. 16's R = R0 fNoise), so the clouds keep the thermals' sizes"),
        port("summary", "Text", "how many thermals, their size range, how many found no room")};
    d.params = {
        intParam("width", 400, "cells", "cells along x", 1, 65536),
        intParam("height", 400, "cells", "cells along y", 1, 65536),
        floatParam("cellSize", 50.0, "m", "edge of one cell", 1e-3, 1e6),
        floatParam("cover", 0.25, "",
                   "fraction of the ground the clouds' density >= 0.5 regions cover (fair-"
                   "weather cumulus: 0.1-0.4)",
                   1e-4, 0.6),
        floatParam("smallestCloud", 200.0, "m", "smallest cloud diameter", 1.0, 1e6),
        floatParam("largestCloud", 2000.0, "m",
                   "largest cloud diameter: the scale break, about the boundary layer's depth", 1.0,
                   1e6),
        floatParam("exponent", -1.7, "",
                   "b of the number density n(l) ~ l^b (-1.7 LES, -1.7 to -2.5 satellites)", -4.0,
                   0.0),
        floatParam("gap", 0.25, "", "neighbours keep this times the larger disk radius apart", 0.0,
                   4.0),
        floatParam("fullScaleCloud", 300.0, "m",
                   "ours: the scale output is l / fullScaleCloud below it, 1 above: about the "
                   "footprint of one copy of the primitive at the mapper's scaleCoefficient "
                   "(300 m: the default primitive at 1.5)",
                   1.0, 1e6),
        intParam("seed", 0, "", "keys every size and position draw", 0)};
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        // Three maps, and the scale map's owners and queue.
        check.checkAllocation("width", {p.getInt("width"), p.getInt("height")},
                              3 * sizeof(float) + sizeof(std::int32_t) + sizeof(std::size_t));
        try {
            algo::checkThermalField(settingsFrom(p));
        } catch (const algo::ThermalFieldError& e) {
            check.fail(paramOf(e.setting()), e.what());
        }
    };
    d.quickParams = {{"width", "40"}, {"height", "40"}};
    d.create = [] { return std::make_unique<ThermalFieldNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
