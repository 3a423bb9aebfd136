#pragma once
/// How far one rendering of a scene lies from another, the reference: the relative error of
/// the beauty's luminance over the cloud's pixels. bench/render_error prints it for the fast
/// mode against the path tracer; a test holds the fast mode to it.

#include <cstddef>
#include <string>

#include <openvdb/openvdb.h>

#include "algo/render/integrators/RenderVolume.h"

namespace cg::algo {

/// Rec. 709 luminance of a linear RGB pixel.
double luminance(const float* rgb);

struct LuminanceError {
    std::size_t pixels = 0;   ///< cloud pixels: reference alpha at least 0.5, luminance > 0
    double ratio = 0.0;       ///< mean L / mean L_ref over them
    double mean = 0.0;        ///< mean of |L − L_ref| / L_ref
    double p90 = 0.0;         ///< its 90th percentile
    double darkMean = 0.0;    ///< its mean over the darker half (by the reference's luminance)
    double brightMean = 0.0;  ///< over the brighter half
};

/// A volume the error is measured on, with the camera and medium it is seen with.
struct ErrorScene {
    openvdb::FloatGrid::Ptr grid;
    RenderSettings settings;
};

/// The synthetic case: graphs/cumulus_still.json's cumulus (seed 3, flat base at 900 m) at
/// `voxelSize` metres, seen by the still's camera, extinction 0.05/m; default image size.
ErrorScene stillCumulusScene(double voxelSize);

/// The three suns the error is measured under, 35° above the horizon: "front" (the camera
/// looks toward it), "beside" (from the camera's right) or "behind" the camera. Throws
/// std::invalid_argument for any other name.
RenderVec3 sunAroundCamera(const RenderCamera& camera, const std::string& where);

/// `image` against `reference` (same size; throws std::invalid_argument otherwise).
LuminanceError luminanceError(const RenderedImage& image, const RenderedImage& reference);

/// How far a reference made of two independent halves a and b (the mean of the two) may lie
/// from converged: the mean over its cloud pixels of |L_a − L_b| / (L_a + L_b), the scale of
/// the mean's own relative error.
double referenceNoise(const RenderedImage& a, const RenderedImage& b);

}  // namespace cg::algo
