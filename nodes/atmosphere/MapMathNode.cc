// MapMath: arithmetic on ground maps, so a painting masks or biases the noise.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "algo/atmosphere/MapOps.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/Map2D.h"

namespace cg {

namespace {

algo::GroundMap groundMap(const Map2DData& m) { return {m.nx, m.ny, m.cellSize, m.values}; }

algo::MapOpSettings settingsFrom(const ParamSet& p)
{
    algo::MapOpSettings s;
    s.op = algo::mapOpFromName(p.getString("op"));
    s.threshold = p.getFloat("threshold");
    s.softness = p.getFloat("softness");
    s.blurRadius = p.getFloat("blurRadius");
    s.low = p.getFloat("low");
    s.high = p.getFloat("high");
    s.gamma = p.getFloat("gamma");
    return s;
}

class MapMathNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const algo::MapOpSettings s = settingsFrom(ctx.params());
        const auto a = ctx.input<Map2DData>("a");
        const auto b = ctx.input<Map2DData>("b");
        if (algo::mapOpIsBinary(s.op) && !b)
            throw InputError(ctx.nodeId() + "/inputs/b",
                             "op '" + ctx.params().getString("op") + "' needs map b");
        const algo::GroundMap ga = groundMap(*a);
        std::optional<algo::GroundMap> gb;
        if (b) gb = groundMap(*b);
        algo::GroundMap out = algo::applyMapOp(ga, gb ? &*gb : nullptr, s);
        ctx.setOutput("map",
                      std::make_shared<Map2DData>(out.nx, out.ny, out.cell, std::move(out.values)));
    }
};

}  // namespace

void registerMapMathNode(Registry& registry)
{
    NodeDecl d;
    d.type = "MapMath";
    d.category = "atmosphere";
    d.doc =
        "Arithmetic on ground maps (ours; the paper has one procedural map), so that a painted "
        "map (ReadMap) masks or biases the noise (NoiseMap): multiply, add, subtract, min, max "
        "of a and b; invert, threshold (a step at threshold, or a smoothstep softness wide), "
        "blur (a Gaussian of standard deviation blurRadius metres, renormalised at the edges) "
        "and remap ([low, high] to [0, 1], then raised to gamma) of a. The result has a's "
        "cells; b is read at a's cell centres, bilinearly in ground metres and clamped at its "
        "edges, so the maps may differ in size and cell. Every result is clamped to [0, 1]. "
        "Feed the result to VapourEmitter's map (where vapour rises) and PrimitiveMapper's "
        "map (each copy's scale and speed, Eq. 16).";
    d.inputs = {
        port("a", "Map2D", "the first map; the result has its cells"),
        port("b", "Map2D", "the second map, for multiply, add, subtract, min and max", true)};
    d.outputs = {port("map", "Map2D", "the result, in [0, 1]")};
    d.params = {
        stringParam(
            "op", "multiply", "the operation",
            {"multiply", "add", "subtract", "min", "max", "invert", "threshold", "blur", "remap"}),
        floatParam("threshold", 0.5, "", "threshold: the level", 0.0, 1.0),
        floatParam("softness", 0.0, "", "threshold: width of the smoothstep (0: a step)", 0.0, 1.0),
        floatParam("blurRadius", 100.0, "m", "blur: the Gaussian's standard deviation", 0.0, 1e6),
        floatParam("low", 0.0, "", "remap: the value that becomes 0", -1e6, 1e6),
        floatParam("high", 1.0, "", "remap: the value that becomes 1", -1e6, 1e6),
        floatParam("gamma", 1.0, "", "remap: exponent after the linear remap", 0.01, 100.0),
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        if (p.getString("op") == "remap" && !(p.getFloat("high") > p.getFloat("low")))
            check.fail("high", "must be above low");
    };
    d.create = [] { return std::make_unique<MapMathNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
