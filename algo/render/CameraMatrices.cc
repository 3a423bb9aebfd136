#include "algo/render/CameraMatrices.h"

#include <algorithm>
#include <cmath>

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

/// The camera's right, up and forward unit vectors in CloudGraph's world (CameraRays' frame).
struct CameraFrame {
    RenderVec3 right, up, forward;
    explicit CameraFrame(const RenderCamera& c)
    {
        forward = (c.lookAt - c.position).unitSafe();
        right = forward.cross(c.up).unitSafe();
        up = right.cross(forward);
    }
};

RenderVec3 toNuke(const RenderVec3& v) { return {v.x(), v.z(), -v.y()}; }
RenderVec3 fromNuke(const RenderVec3& v) { return {v.x(), -v.z(), v.y()}; }

/// R = Ry(b) Rx(a) Rz(c), column vectors (Nuke's ZXY order), as rows.
std::array<RenderVec3, 3> nukeRotation(const RenderVec3& degrees)
{
    const double a = degrees.x() * kDegree, b = degrees.y() * kDegree, c = degrees.z() * kDegree;
    const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b),
                 cc = std::cos(c), sc = std::sin(c);
    // Columns of Ry Rx: (cb, 0, -sb), (sb sa, ca, cb sa), (sb ca, -sa, cb ca); then Rz mixes
    // the first two.
    const RenderVec3 c0(cb, 0.0, -sb), c1(sb * sa, ca, cb * sa), c2(sb * ca, -sa, cb * ca);
    const RenderVec3 x = c0 * cc + c1 * sc, y = c1 * cc - c0 * sc;
    return {RenderVec3(x.x(), y.x(), c2.x()), RenderVec3(x.y(), y.y(), c2.y()),
            RenderVec3(x.z(), y.z(), c2.z())};
}

}  // namespace

Matrix44 worldToCamera(const RenderCamera& camera)
{
    const CameraFrame f(camera);
    const RenderVec3& p = camera.position;
    Matrix44 m{};
    for (int a = 0; a < 3; ++a) {
        m[a][0] = f.right[a];
        m[a][1] = f.up[a];
        m[a][2] = f.forward[a];
    }
    m[3][0] = -f.right.dot(p);
    m[3][1] = -f.up.dot(p);
    m[3][2] = -f.forward.dot(p);
    m[3][3] = 1.0;
    return m;
}

Matrix44 worldToNdc(const RenderCamera& camera)
{
    // Camera space to NDC: x_ndc = 0.5 x / (z t aspect) + 0.5, y_ndc = 0.5 - 0.5 y / (z t),
    // t = tan(fov / 2), as CameraRays aims pixel centres; w = z.
    const double t = std::tan(0.5 * camera.fovDegrees * kDegree);
    const double aspect = double(camera.width) / double(camera.height);
    const Matrix44 toCamera = worldToCamera(camera);
    Matrix44 project{};
    project[0][0] = 0.5 / (t * aspect);
    project[1][1] = -0.5 / t;
    project[2][0] = 0.5;
    project[2][1] = 0.5;
    project[2][3] = 1.0;
    project[3][2] = 1.0;
    Matrix44 m{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            for (int k = 0; k < 4; ++k) m[r][c] += toCamera[r][k] * project[k][c];
    return m;
}

void projectToNdc(const Matrix44& m, const RenderVec3& p, double ndc[2])
{
    double out[4] = {0.0, 0.0, 0.0, 0.0};
    const double v[4] = {p.x(), p.y(), p.z(), 1.0};
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k) out[c] += v[k] * m[k][c];
    ndc[0] = out[0] / out[3];
    ndc[1] = out[1] / out[3];
}

NukePose nukePose(const RenderCamera& camera)
{
    const CameraFrame f(camera);
    // The camera's axes in Nuke's world: x = right, y = up, z = backward; M's columns.
    const RenderVec3 x = toNuke(f.right), y = toNuke(f.up), z = toNuke(-f.forward);
    // M = Ry(b) Rx(a) Rz(c): M12 = -sin a, M02 / M22 = tan b, M10 / M11 = tan c.
    const double a = std::asin(std::clamp(-z.y(), -1.0, 1.0));
    double b = 0.0, c = 0.0;
    if (std::abs(z.y()) < 1.0 - 1e-12) {
        b = std::atan2(z.x(), z.z());
        c = std::atan2(x.y(), y.y());
    } else {
        // Straight up or down: only b + c or b - c is fixed; take b = 0, so M = Rx Rz.
        c = std::atan2(-y.x(), x.x());
    }
    NukePose pose;
    pose.translate = toNuke(camera.position);
    pose.rotateDegrees = RenderVec3(a, b, c) * (1.0 / kDegree);
    pose.verticalFovDegrees = camera.fovDegrees;
    return pose;
}

CameraKey keyFromNukePose(double frame, const NukePose& pose)
{
    const std::array<RenderVec3, 3> rows = nukeRotation(pose.rotateDegrees);
    const RenderVec3 up(rows[0].y(), rows[1].y(), rows[2].y());
    const RenderVec3 back(rows[0].z(), rows[1].z(), rows[2].z());
    CameraKey key;
    key.frame = frame;
    key.position = fromNuke(pose.translate);
    key.lookAt = key.position + fromNuke(-back) * 1000.0;
    key.up = fromNuke(up);
    key.fovDegrees = pose.verticalFovDegrees;
    return key;
}

}  // namespace cg::algo
