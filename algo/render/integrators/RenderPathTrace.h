#pragma once
/// The reference renderer: an unbiased Monte Carlo volumetric path tracer for the same scene
/// the fast renderer approximates (fog volume, distant sun, sky dome, Lambertian ground).
///
/// Free flights are sampled by delta tracking and shadow rays toward the sun are estimated by
/// ratio tracking (Novák et al. 2014), both against per-block majorants of the density
/// (RenderOccupancy) so empty space costs one DDA step per 8³ block. At every scattering
/// event the sun is sampled directly (next-event estimation); the next direction is drawn
/// from the phase function; a path that leaves the volume sees the sky (ambient × sky
/// radiance) or bounces off the ground (sun by next-event estimation, cosine-distributed
/// bounce). Russian roulette ends paths of low throughput; `maxBounces` cuts the rest, the
/// one bias, far below the noise at the default.
///
/// Each pixel's paths draw from a counter-based generator keyed by (seed, pixel, sample), so
/// the image is bit-identical for any thread count. Output as renderFogVolume: beauty RGBA
/// (alpha = 1 − the mean transmittance of the camera ray) and the background layer.

#include <functional>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"
#include "algo/render/integrators/RenderVolume.h"

namespace cg::algo {

/// Path-traces `grid` (density, linear transform, metres) with settings.pathTrace.samples
/// paths a pixel. Throws std::invalid_argument for unusable settings (as renderFogVolume,
/// and samples or maxBounces below 1). `cancelled` is polled once a row.
RenderedImage renderPathTraced(const openvdb::FloatGrid& grid, const RenderSettings& settings,
                               const std::function<bool()>& cancelled = {});

}  // namespace cg::algo
