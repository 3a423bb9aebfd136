#pragma once
/// A camera that moves: keys at frames, each a pinhole camera (position, look-at point, up,
/// vertical field of view), interpolated between them. Between keys every quantity follows a
/// cubic Hermite curve in the frame whose tangents are the Catmull-Rom ones for unevenly
/// spaced keys, (p[i+1] - p[i-1]) / (f[i+1] - f[i-1]), one-sided at the first and last key: a
/// path through every key with a continuous velocity, the spline layout artists expect from
/// a camera. Before the first key and after the last the camera holds. On a key's frame the
/// camera is that key's, exactly. No engine includes.

#include <vector>

#include "algo/render/RenderSettings.h"

namespace cg::algo {

struct CameraKey {
    double frame = 0.0;
    RenderVec3 position{0.0, 0.0, 0.0};  ///< m
    RenderVec3 lookAt{0.0, 0.0, 1.0};    ///< m
    RenderVec3 up{0.0, 0.0, 1.0};
    double fovDegrees = 40.0;  ///< vertical
};

/// Throws std::invalid_argument naming the key (from 0) that is unusable: frames not strictly
/// increasing, a field of view outside (0, 180), a key looking at its own position or along
/// its up, or a value that is not finite. No keys is refused too.
void checkCameraKeys(const std::vector<CameraKey>& keys);

/// The camera at `frame` on the path through `keys`, which checkCameraKeys has accepted (not
/// checked again: a writer asks for every frame of a shot), with `base`'s image size. With
/// `easeEnds` the tangents at the first and last key are zero instead of one-sided, so the
/// camera starts from rest and comes to rest (an ease in and out, as a layout artist keys a
/// move from a hold); the inner keys keep their Catmull-Rom tangents.
RenderCamera cameraOnPath(const std::vector<CameraKey>& keys, double frame,
                          const RenderCamera& base, bool easeEnds = false);

}  // namespace cg::algo
