#include "golden/GoldenSpecs.h"

#include <nlohmann/json.hpp>

#include "core/Graph.h"

namespace cg::golden {

namespace {

void set(Graph& g, const std::string& node, const std::string& param, const nlohmann::json& value)
{
    g.setParam(node, param, value, "golden " + node + "." + param);
}

/// A primitive of 644 cloud particles in about a second and a half: a small box (400 x 400 x
/// 700 m, the default lattice) over 40 frames; the source, half the default's, is saturated
/// so that it condenses before it reaches the lid.
void smallPrimitive(Graph& g, const std::string& node)
{
    set(g, node, "frames", 40);
    set(g, node, "width", 400.0);
    set(g, node, "height", 700.0);
    set(g, node, "sourceHeight", 100.0);
    set(g, node, "sourceRadius", 125.0);
    set(g, node, "sourceHumidity", 1.0);
}

const ParamSet& paramsOf(const Graph& g, const std::string& node)
{
    return g.nodes()[g.indexOf(node)].params;
}

/// Halves the map's resolution on cells twice as large: the same ground (its largest
/// wavelength too), a quarter of the vapour.
void coarserMap(Graph& g)
{
    const ParamSet& p = paramsOf(g, "noise");
    set(g, "noise", "cellSize", p.getFloat("cellSize") * 2);
    set(g, "noise", "width", p.getInt("width") / 2);
    set(g, "noise", "height", p.getInt("height") / 2);
    set(g, "noise", "largestWavelength", p.getFloat("largestWavelength") / 2);
}

/// Voxels twice as large (an eighth of them); the radius in metres stays.
void coarserVoxels(Graph& g, const std::string& node)
{
    set(g, node, "voxelSize", paramsOf(g, node).getFloat("voxelSize") * 2);
}

/// The figure graphs share one wiring: a coarser map, the small primitive, coarser voxels and
/// a thumbnail render. Mapper settings, camera and lighting stay as shipped.
void smallFigure(Graph& g)
{
    coarserMap(g);
    smallPrimitive(g, "primitive");
    coarserVoxels(g, "voxelize");
    set(g, "render", "width", 96);
    set(g, "render", "height", 64);
}

/// A thermal field on cells twice as large: the same ground and thermals, a quarter of the
/// vapour; then the figures' small primitive, coarser voxels and a thumbnail.
void smallField(Graph& g)
{
    const ParamSet& p = paramsOf(g, "thermals");
    set(g, "thermals", "cellSize", p.getFloat("cellSize") * 2);
    set(g, "thermals", "width", p.getInt("width") / 2);
    set(g, "thermals", "height", p.getInt("height") / 2);
    smallPrimitive(g, "primitive");
    coarserVoxels(g, "voxelize");
    set(g, "render", "width", 96);
    set(g, "render", "height", 64);
}

std::vector<GoldenSpec> makeSpecs()
{
    const std::vector<std::string> video = {"video"};  // runs ffmpeg; its MP4 bytes are ffmpeg's
    // Figure frames: 61 is the last frame before condensation (every vapour particle of every
    // figure graph condenses at 62), 150 has mapped levels 1-2 (t_s[2] = 112, Figure 5: 162),
    // 300 levels up to 5 and the frame the VDB (every 100) and PLY (every 20) writers write.
    const std::vector<int> figureFrames = {61, 150, 300};
    return {
        // 0 writes the map; 91 is the last frame before condensation (92); the particles are
        // written every 10 frames, so 150 and 290 but not 91.
        {"atmosphere", {0, 91, 150, 290}, coarserMap, {}},
        // The art-direction example (user guide section 12): the painted arc, the hero and the
        // moving camera at frames 150 (the hero alone) and 300 (the arc's clouds, the first
        // camera key); its Retime and video act on frame 491 only (the video is left out).
        {"art_direction", {150, 300}, smallFigure, video},
        // A storm's hour: grown (150), mature with its anvil (300), decaying (450).
        {"cumulonimbus_life", {150, 300, 450}, smallFigure, video},
        // The hour of cumulus: its field grown (300), and its clouds coming and going (600:
        // early thermals' clouds evaporating, later ones forming).
        {"cumulus_day", {300, 600}, smallField, {}},
        {"cumulus_still",
         {0},
         [](Graph& g) {
             set(g, "cloud", "voxelSize", 30.0);
             set(g, "render", "width", 80);
             set(g, "render", "height", 60);
         },
         {}},
        {"default",
         {0, 10, 23},
         [](Graph& g) {
             set(g, "field", "width", 64);
             set(g, "field", "height", 64);
         },
         {}},
        {"figure1_cloudscape", figureFrames, smallFigure, video},
        // Issue 17's 20 km field: the same small wiring (its copies are the small primitive's).
        {"cloudscape_20km", figureFrames, smallFigure, video},
        {"figure5_progress", figureFrames,
         [](Graph& g) {
             smallFigure(g);
             coarserVoxels(g, "vapourVolume");  // CombineVolumes needs the same grid
         },
         video},
        {"figure6_towering_cumulus", figureFrames, smallFigure, video},
        {"figure7a_beta33", figureFrames, smallFigure, video},
        {"figure7b_beta27", figureFrames, smallFigure, video},
        {"figure8_cumulonimbus", figureFrames, smallFigure, video},
        // Its sounding variant feeds its towers for the whole run: fewer of them here.
        {"figure8_cumulonimbus_sounding",
         {150, 300},
         [](Graph& g) {
             smallFigure(g);
             set(g, "emit", "maxParticlesPerCell", 0.6);
         },
         video},
        {"figure9_sparse", figureFrames, smallFigure, video},
        {"primitive", {0}, [](Graph& g) { smallPrimitive(g, "sim"); }, {}},
        // Issue 14's sounding graphs: the tower half-way and at the top, the field rising and
        // capped.
        {"sounding_cumulonimbus", {150, 300}, smallFigure, {}},
        {"sounding_cumulus", {120, 240}, smallFigure, video},
        // The primitive's middle and last frames (PrimitiveFrame plays frame s at frame s).
        {"primitive_render",
         {20, 39},
         [](Graph& g) {
             smallPrimitive(g, "sim");
             coarserVoxels(g, "voxelize");
             set(g, "render", "width", 40);
             set(g, "render", "height", 50);
         },
         {}},
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
