#pragma once
/// Arithmetic on ground maps (the density maps of Eq. 3-4 and 16), so that a painting can
/// mask or bias the 1/f^beta noise (ours; the paper has one procedural map). A map is nx x ny
/// cells of `cell` metres, row-major, its corner at the ground's origin, values in [0, 1];
/// every result is clamped to [0, 1]. No engine includes.

#include <string>
#include <vector>

namespace cg::algo {

struct GroundMap {
    int nx = 0, ny = 0;
    double cell = 1.0;          ///< m
    std::vector<float> values;  ///< index iy * nx + ix
};

enum class MapOp { Multiply, Add, Subtract, Min, Max, Invert, Threshold, Blur, Remap };

/// "multiply", "add", ...; std::invalid_argument for another name.
MapOp mapOpFromName(const std::string& name);
/// Whether the operation reads a second map.
bool mapOpIsBinary(MapOp op);

struct MapOpSettings {
    MapOp op = MapOp::Multiply;
    double threshold = 0.5;        ///< Threshold: the level
    double softness = 0.0;         ///< Threshold: width of the smoothstep around it (0: a step)
    double blurRadius = 0.0;       ///< Blur: the Gaussian's standard deviation, m
    double low = 0.0, high = 1.0;  ///< Remap: [low, high] to [0, 1]
    double gamma = 1.0;            ///< Remap: then raised to this power
};

/// The operation on `a` (and `b`, read at a's cell centres bilinearly in ground metres,
/// clamped at its edges, so the two may differ in size and cell). The result has a's grid.
/// Throws std::invalid_argument for a missing b or unusable settings.
GroundMap applyMapOp(const GroundMap& a, const GroundMap* b, const MapOpSettings& settings);

/// b's value at ground point (x, y), bilinear between cell centres, clamped at the edges.
float sampleGroundMap(const GroundMap& b, double x, double y);

}  // namespace cg::algo
