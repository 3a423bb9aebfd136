#include "golden/GoldenSpecs.h"

#include <nlohmann/json.hpp>

#include "core/Graph.h"

namespace cg::golden {

namespace {

void set(Graph& g, const std::string& node, const std::string& param, const nlohmann::json& value)
{
    g.setParam(node, param, value, "golden " + node + "." + param);
}

/// A primitive of 644 cloud particles in about a second and a half: an eighth of the default
/// box (half as wide and high, the same lattice) over 40 frames; the source, scaled with the
/// box, is saturated so that it condenses before it reaches the lid.
void smallPrimitive(Graph& g, const std::string& node)
{
    set(g, node, "frames", 40);
    set(g, node, "width", 400.0);
    set(g, node, "height", 700.0);
    set(g, node, "sourceHeight", 100.0);
    set(g, node, "sourceRadius", 125.0);
    set(g, node, "sourceHumidity", 1.0);
}

/// The figure graphs share one wiring: a map half as wide on cells twice as large (same
/// ground, a quarter of the vapour), the small primitive, voxels twice as large and a
/// thumbnail render. Mapper settings, camera and lighting stay as shipped.
void smallFigure(Graph& g, int width, int height, double cellSize, double voxelSize)
{
    set(g, "noise", "width", width / 2);
    set(g, "noise", "height", height / 2);
    set(g, "noise", "cellSize", cellSize * 2);
    smallPrimitive(g, "primitive");
    set(g, "voxelize", "voxelSize", voxelSize * 2);
    set(g, "render", "width", 96);
    set(g, "render", "height", 64);
}

std::vector<GoldenSpec> makeSpecs()
{
    const std::vector<std::string> video = {"video"};  // runs ffmpeg; its MP4 bytes are ffmpeg's
    return {
        {"atmosphere", {0, 100, 200}, [](Graph& g) {
             set(g, "noise", "width", 32);
             set(g, "noise", "height", 32);
         }, {}},
        {"cumulus_still", {0}, [](Graph& g) {
             set(g, "cloud", "voxelSize", 30.0);
             set(g, "render", "width", 80);
             set(g, "render", "height", 60);
         }, {}},
        {"default", {0, 10, 23}, [](Graph& g) {
             set(g, "field", "width", 64);
             set(g, "field", "height", 64);
         }, {}},
        {"figure1_cloudscape", {100, 200, 300}, [](Graph& g) { smallFigure(g, 300, 300, 50, 40); }, video},
        {"figure5_progress", {100, 200, 300}, [](Graph& g) {
             smallFigure(g, 300, 125, 50, 80);
             set(g, "vapourVolume", "voxelSize", 160.0);
         }, video},
        {"figure6_towering_cumulus", {100, 200, 300}, [](Graph& g) { smallFigure(g, 64, 64, 100, 40); }, video},
        {"figure7a_beta33", {100, 200, 300}, [](Graph& g) { smallFigure(g, 150, 100, 50, 40); }, video},
        {"figure7b_beta27", {100, 200, 300}, [](Graph& g) { smallFigure(g, 200, 100, 50, 40); }, video},
        {"figure8_cumulonimbus", {100, 200, 300}, [](Graph& g) { smallFigure(g, 300, 100, 50, 80); }, video},
        {"figure9_sparse", {100, 200, 300}, [](Graph& g) { smallFigure(g, 300, 300, 50, 40); }, video},
        {"primitive", {0}, [](Graph& g) { smallPrimitive(g, "sim"); }, {}},
        {"primitive_render", {20, 39}, [](Graph& g) {
             smallPrimitive(g, "sim");
             set(g, "voxelize", "voxelSize", 16.0);
             set(g, "render", "width", 40);
             set(g, "render", "height", 50);
         }, {}},
    };
}

}  // namespace

const std::vector<GoldenSpec>& goldenSpecs()
{
    static const std::vector<GoldenSpec> specs = makeSpecs();
    return specs;
}

const GoldenSpec* findSpec(const std::string& name)
{
    for (const GoldenSpec& s : goldenSpecs())
        if (s.name == name) return &s;
    return nullptr;
}

}  // namespace cg::golden
