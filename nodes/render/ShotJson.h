#pragma once
/// The shot as another renderer needs it to light and frame CloudGraph's volumes the same way
/// (the Blender add-on reads it): WriteShot's JSON file, version 1. Units: metres, z up,
/// linear Rec.709 radiance; angles in degrees.

#include <string>

#include "algo/render/RenderSettings.h"

namespace cg {

class CameraPathData;

/// The sun, sky, ground and medium (after the volume's optics replaced the parameters) as a
/// JSON object, for the Renderer's `lighting` output.
std::string lightingJson(const algo::RenderSettings& settings);

/// The whole file: frames first..last (each frameTime seconds), the image size and camera of
/// every frame from `path`, and `lighting` (lightingJson's text) as it is. Throws
/// std::invalid_argument when `lighting` is not a JSON object.
std::string shotJson(const CameraPathData& path, int first, int last, double frameTime,
                     const std::string& lighting);

}  // namespace cg
