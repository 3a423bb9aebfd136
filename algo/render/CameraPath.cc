#include "algo/render/CameraPath.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace cg::algo {

namespace {

bool finite(const RenderVec3& v)
{
    return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

/// Hermite basis weights at s in [0, 1] for p0, the tangent at 0 (times the span), p1 and
/// the tangent at 1 (times the span).
struct Hermite {
    double p0, m0, p1, m1;
    explicit Hermite(double s)
    {
        const double s2 = s * s, s3 = s2 * s;
        p0 = 2.0 * s3 - 3.0 * s2 + 1.0;
        m0 = s3 - 2.0 * s2 + s;
        p1 = -2.0 * s3 + 3.0 * s2;
        m1 = s3 - s2;
    }
};

/// The Catmull-Rom tangent at key i of the values `at(k)` (per frame), one-sided at the ends,
/// or zero there when the path eases.
template <typename T, typename At>
T tangent(const std::vector<CameraKey>& keys, std::size_t i, At at, bool easeEnds)
{
    if (easeEnds && (i == 0 || i + 1 == keys.size())) return at(keys[i]) * 0.0;
    const std::size_t lo = i == 0 ? 0 : i - 1;
    const std::size_t hi = i + 1 == keys.size() ? i : i + 1;
    return (at(keys[hi]) - at(keys[lo])) * (1.0 / (keys[hi].frame - keys[lo].frame));
}

template <typename T, typename At>
T interpolate(const std::vector<CameraKey>& keys, std::size_t i, double frame, At at, bool easeEnds)
{
    const double span = keys[i + 1].frame - keys[i].frame;
    const Hermite h((frame - keys[i].frame) / span);
    const T m0 = tangent<T>(keys, i, at, easeEnds), m1 = tangent<T>(keys, i + 1, at, easeEnds);
    return at(keys[i]) * h.p0 + m0 * (h.m0 * span) + at(keys[i + 1]) * h.p1 + m1 * (h.m1 * span);
}

void fail(std::size_t key, const std::string& what)
{
    throw std::invalid_argument("camera key " + std::to_string(key) + ": " + what);
}

}  // namespace

void checkCameraKeys(const std::vector<CameraKey>& keys)
{
    if (keys.empty()) throw std::invalid_argument("camera path: no keys");
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const CameraKey& k = keys[i];
        if (!std::isfinite(k.frame) || !finite(k.position) || !finite(k.lookAt) || !finite(k.up) ||
            !std::isfinite(k.fovDegrees))
            fail(i, "a value is not finite");
        if (i > 0 && !(k.frame > keys[i - 1].frame))
            fail(i, "its frame must come after the key before it");
        if (!(k.fovDegrees > 0.0 && k.fovDegrees < 180.0))
            fail(i, "the field of view must be in (0, 180) degrees");
        const RenderVec3 view = k.lookAt - k.position;
        if (!(view.length() > 0.0)) fail(i, "it looks at its own position");
        if (!(view.cross(k.up).length() > 1e-9 * view.length() * k.up.length()))
            fail(i, "its up is zero or along the view direction");
    }
}

RenderCamera cameraOnPath(const std::vector<CameraKey>& keys, double frame,
                          const RenderCamera& base, bool easeEnds)
{
    RenderCamera camera = base;
    const auto take = [&camera](const CameraKey& k) {
        camera.position = k.position;
        camera.lookAt = k.lookAt;
        camera.up = k.up;
        camera.fovDegrees = k.fovDegrees;
        return camera;
    };
    if (!(frame > keys.front().frame)) return take(keys.front());
    if (!(frame < keys.back().frame)) return take(keys.back());
    // The last key at or before the frame; the checks above keep it below the last key.
    const auto after = std::upper_bound(keys.begin(), keys.end(), frame,
                                        [](double f, const CameraKey& k) { return f < k.frame; });
    const auto i = static_cast<std::size_t>(after - keys.begin()) - 1;
    if (keys[i].frame == frame) return take(keys[i]);
    camera.position = interpolate<RenderVec3>(
        keys, i, frame, [](const CameraKey& k) { return k.position; }, easeEnds);
    camera.lookAt = interpolate<RenderVec3>(
        keys, i, frame, [](const CameraKey& k) { return k.lookAt; }, easeEnds);
    camera.up = interpolate<RenderVec3>(
        keys, i, frame, [](const CameraKey& k) { return k.up; }, easeEnds);
    // The spline may overshoot between keys; the field of view stays a field of view.
    camera.fovDegrees =
        std::clamp(interpolate<double>(
                       keys, i, frame, [](const CameraKey& k) { return k.fovDegrees; }, easeEnds),
                   1e-3, 179.999);
    return camera;
}

}  // namespace cg::algo
