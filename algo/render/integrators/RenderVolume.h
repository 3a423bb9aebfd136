#pragma once
/// Single-pass volume renderer for cloud fog volumes: camera rays are marched through the
/// occupied leaf blocks of the VDB tree; each sample adds light from the sun (optical depth
/// from a precomputed light map, Henyey-Greenstein phase, multiple scattering by octaves) and
/// from the sky (occluded by the optical depth straight up); behind the volume is the ground
/// plane z = 0 (lit, shadowed by the cloud, hazed with distance) or the sky gradient.
/// See docs/rendering.md for the model.
///
/// Output is linear radiance (scene-referred, before exposure and tone mapping), RGBA with 4
/// floats per pixel, top row first; alpha is the volume's opacity 1 − T along the pixel's ray,
/// and RGB already contains what lies behind the volume; `background` holds that radiance on
/// its own, so the cloud alone is derived as RGB − (1 − alpha) background (CloudLayer.h).
/// Every pixel is computed
/// independently (jitter is counter-based on the pixel index), so the image does not depend
/// on thread count.

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderRays.h"
#include "algo/render/RenderSettings.h"

namespace cg::algo {

struct RenderedImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  ///< 4 floats per pixel, top row first: the beauty
    /// 3 floats (linear RGB) per pixel, top row first: the radiance behind the volume along
    /// the pixel's ray (the sky, or the ground lit by sun and sky with the cloud's shadow,
    /// hazed), before the volume's transmittance; empty where a renderer has none.
    std::vector<float> background;
    /// With RenderSettings::aovs (the fast renderer; empty otherwise), per pixel, top row first:
    /// the cloud's light (premultiplied, background excluded) from the sun (direct and
    /// bounced, the sun-lit ground's glow included) and from the sky, whose sum is the cloud
    /// layer, 3 floats each; the depth, 1 float: the camera-space depth (m along the view
    /// axis) of the cloud's light, the mean of its samples' depths weighted by what each adds
    /// to the opacity, where no cloud the ground's depth, on the sky kNoDepth; the ground's
    /// shadow matte, 1 float: the fraction of the direct sun the cloud takes from the ground
    /// seen through the pixel (0 on the sky and out of the shadow).
    std::vector<float> sun, sky, depth, shadow;
};

/// The depth of a pixel that sees only sky (Blender's convention).
inline constexpr float kNoDepth = 1e10f;

/// Renders `grid` (density in [0, 1], linear transform, metres). Throws std::invalid_argument
/// for unusable settings (size < 1, field of view outside (0, 180), camera looking at itself
/// or along `up`, non-positive steps, a non-linear transform). `cancelled` is polled from
/// worker threads; once it returns true the remaining rows are skipped (the caller discards
/// the image).
RenderedImage renderFogVolume(const openvdb::FloatGrid& grid, const RenderSettings& settings,
                              const std::function<bool()>& cancelled = {});

/// Transmittance exp(−∫ σ_t ds) of `grid` along the world ray origin + s * direction, s >= 0,
/// with σ_t = extinction (1/m) × density, marched exactly as camera rays are (midpoint samples
/// every stepVoxels voxels, no jitter, no early stop).
double fogTransmittance(const openvdb::FloatGrid& grid, const RenderVec3& origin,
                        const RenderVec3& direction, double extinction, double stepVoxels);

}  // namespace cg::algo
