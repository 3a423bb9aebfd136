// Camera moves and the camera in other tools' forms (algo/render/CameraPath.h,
// CameraMatrices.h): keys reproduced exactly, a spline that keeps linear motion linear and its
// velocity continuous, and OpenEXR's and Nuke's matrices that project a point where the
// Renderer's rays put it, the Nuke pose checked with rotation matrices built here.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "algo/render/CameraMatrices.h"
#include "algo/render/CameraPath.h"
#include "algo/render/RenderRays.h"

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;

CameraKey key(double frame, RenderVec3 position, RenderVec3 lookAt, double fov)
{
    CameraKey k;
    k.frame = frame;
    k.position = position;
    k.lookAt = lookAt;
    k.fovDegrees = fov;
    return k;
}

RenderCamera camera(RenderVec3 position, RenderVec3 lookAt, RenderVec3 up, double fov)
{
    RenderCamera c;
    c.position = position;
    c.lookAt = lookAt;
    c.up = up;
    c.fovDegrees = fov;
    c.width = 640;
    c.height = 360;
    return c;
}

/// Cameras seen from the side, from below, tilted down and rolled.
std::vector<RenderCamera> cameras()
{
    return {camera({3200, -6500, 2000}, {3200, 3200, 4000}, {0, 0, 1}, 45),
            camera({-500, 200, 50}, {1000, 2500, 3000}, {0, 0, 1}, 70),
            camera({0, -8000, 9000}, {500, 0, 0}, {0, 0, 1}, 30),
            camera({100, -2000, 800}, {0, 0, 1500}, {0.3, 0.1, 1}, 55)};
}

/// Rotation about one axis by `degrees`, column vectors, as 3 x 3 rows.
using M3 = std::array<std::array<double, 3>, 3>;
M3 rotation(int axis, double degrees)
{
    const double c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
    M3 m{};
    m[axis][axis] = 1;
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    m[i][i] = c, m[i][j] = -s, m[j][i] = s, m[j][j] = c;
    return m;
}
M3 product(const M3& a, const M3& b)
{
    M3 m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) m[r][c] += a[r][k] * b[k][c];
    return m;
}

}  // namespace

TEST(CameraPath, AKeysFrameIsTheKeyAndTheEndsHold)
{
    const std::vector<CameraKey> keys = {key(0, {0, -4000, 800}, {0, 0, 1200}, 40),
                                         key(12, {300, -3500, 900}, {10, 0, 1300}, 35),
                                         key(40, {900, -2500, 1500}, {50, 20, 1500}, 50)};
    const RenderCamera base;
    for (const CameraKey& k : keys)
        for (double frame : {k.frame}) {
            const RenderCamera c = cameraOnPath(keys, frame, base);
            EXPECT_EQ(c.position, k.position);
            EXPECT_EQ(c.lookAt, k.lookAt);
            EXPECT_EQ(c.fovDegrees, k.fovDegrees);
        }
    EXPECT_EQ(cameraOnPath(keys, -5, base).position, keys.front().position);
    EXPECT_EQ(cameraOnPath(keys, 400, base).position, keys.back().position);
    EXPECT_EQ(cameraOnPath(keys, 7, base).width, base.width);
}

TEST(CameraPath, UnevenKeysOnALineGiveMotionAlongItAtConstantSpeed)
{
    // Catmull-Rom tangents of linear data are its slope, so the Hermite path is the line.
    const RenderVec3 p0(100, -4000, 800), v(12.5, 40, -3);
    std::vector<CameraKey> keys;
    for (double f : {0.0, 3.0, 10.0, 11.0, 30.0})
        keys.push_back(key(f, p0 + v * f, {0, 0, 1200}, 40 + 0.5 * f));
    for (double f = 0; f <= 30; f += 0.37) {
        const RenderCamera c = cameraOnPath(keys, f, RenderCamera{});
        EXPECT_NEAR((c.position - (p0 + v * f)).length(), 0.0, 1e-9) << f;
        EXPECT_NEAR(c.fovDegrees, 40 + 0.5 * f, 1e-12) << f;
    }
}

TEST(CameraPath, TheVelocityIsContinuousThroughAKey)
{
    const std::vector<CameraKey> keys = {key(0, {0, -4000, 800}, {0, 0, 1200}, 40),
                                         key(10, {800, -3000, 1500}, {0, 0, 1200}, 40),
                                         key(25, {900, -1000, 900}, {0, 0, 1200}, 40)};
    const double h = 1e-4;
    const auto at = [&](double f) { return cameraOnPath(keys, f, RenderCamera{}).position; };
    const RenderVec3 before = (at(10) - at(10 - h)) * (1 / h),
                     after = (at(10 + h) - at(10)) * (1 / h);
    EXPECT_LT((before - after).length(), 1e-2 * before.length());
    // The tangent there is the Catmull-Rom one: (p2 - p0) / (f2 - f0).
    const RenderVec3 expected = (keys[2].position - keys[0].position) * (1.0 / 25.0);
    EXPECT_LT((after - expected).length(), 1e-2 * expected.length());
}

TEST(CameraPath, UnusableKeysAreRefusedNamingTheKey)
{
    const CameraKey good = key(0, {0, -4000, 800}, {0, 0, 1200}, 40);
    const auto refused = [](std::vector<CameraKey> keys, const std::string& what) {
        try {
            checkCameraKeys(keys);
            ADD_FAILURE() << what << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    refused({}, "no keys");
    CameraKey k = good;
    k.frame = 0;
    refused({good, k}, "camera key 1: its frame must come after");
    k = good;
    k.fovDegrees = 180;
    refused({k}, "camera key 0: the field of view");
    k = good;
    k.lookAt = k.position;
    refused({k}, "looks at its own position");
    k = good;
    k.up = k.lookAt - k.position;
    refused({k}, "its up is zero or along the view");
    k = good;
    k.position[1] = std::nan("");
    refused({k}, "not finite");
}

TEST(CameraMatrices, WorldToNdcPutsEachPixelsRayOnThatPixel)
{
    for (const RenderCamera& c : cameras()) {
        const CameraRays rays(c);
        const Matrix44 m = worldToNdc(c);
        for (int px : {0, 17, 320, 639})
            for (int py : {0, 100, 359}) {
                const RenderVec3 p = c.position + rays.direction(px, py) * 2345.0;
                double ndc[2];
                projectToNdc(m, p, ndc);
                EXPECT_NEAR(ndc[0] * c.width - 0.5, px, 1e-6);
                EXPECT_NEAR(ndc[1] * c.height - 0.5, py, 1e-6);
            }
        // worldToCamera: the camera at the origin, the view along +z, up along +y.
        const Matrix44 w = worldToCamera(c);
        const RenderVec3 ahead = c.position + (c.lookAt - c.position).unitSafe() * 100.0;
        double cam[3] = {0, 0, 0};
        for (int col = 0; col < 3; ++col)
            cam[col] =
                ahead.x() * w[0][col] + ahead.y() * w[1][col] + ahead.z() * w[2][col] + w[3][col];
        EXPECT_NEAR(cam[0], 0.0, 1e-9);
        EXPECT_NEAR(cam[1], 0.0, 1e-9);
        EXPECT_NEAR(cam[2], 100.0, 1e-9);
    }
}

TEST(CameraMatrices, TheNukePoseProjectsEachPixelsRayOnThatPixel)
{
    for (const RenderCamera& c : cameras()) {
        const NukePose pose = nukePose(c);
        // Nuke's camera: R = Ry Rx Rz (order ZXY), looking down its -z, y up, in a y-up world
        // where CloudGraph's (x, y, z) is (x, z, -y).
        const M3 r = product(
            product(rotation(1, pose.rotateDegrees.y()), rotation(0, pose.rotateDegrees.x())),
            rotation(2, pose.rotateDegrees.z()));
        const double t = std::tan(0.5 * pose.verticalFovDegrees * kPi / 180);
        const CameraRays rays(c);
        for (int px : {0, 200, 639})
            for (int py : {0, 180, 359}) {
                const RenderVec3 w = c.position + rays.direction(px, py) * 3000.0;
                const double nuke[3] = {w.x() - pose.translate.x(), w.z() - pose.translate.y(),
                                        -w.y() - pose.translate.z()};
                double local[3] = {0, 0, 0};  // R^T (p - t)
                for (int a = 0; a < 3; ++a)
                    for (int k = 0; k < 3; ++k) local[a] += r[k][a] * nuke[k];
                const double sx = local[0] / (-local[2] * t), sy = local[1] / (-local[2] * t);
                const double aspect = double(c.width) / c.height;
                EXPECT_NEAR((sx / aspect + 1) / 2 * c.width - 0.5, px, 1e-6);
                EXPECT_NEAR((1 - sy) / 2 * c.height - 0.5, py, 1e-6);
            }
        // And back: the same view, up and field of view.
        const CameraKey back = keyFromNukePose(0.0, pose);
        EXPECT_LT((back.position - c.position).length(), 1e-9);
        const RenderVec3 view = (c.lookAt - c.position).unitSafe();
        EXPECT_LT(((back.lookAt - back.position).unitSafe() - view).length(), 1e-12);
        EXPECT_EQ(back.fovDegrees, c.fovDegrees);
        const CameraRays again(
            RenderCamera{back.position, back.lookAt, back.up, back.fovDegrees, c.width, c.height});
        EXPECT_LT((again.direction(3, 5) - rays.direction(3, 5)).length(), 1e-12);
    }
}

TEST(CameraPath, AnEasedPathStartsAndEndsAtRestAndStillPassesThroughItsKeys)
{
    const std::vector<CameraKey> keys = {key(300, {7000, -4000, 8000}, {3600, 2900, 2000}, 45),
                                         key(400, {7000, -3700, 4000}, {4000, 3300, 2600}, 50),
                                         key(491, {7000, -3500, 900}, {4200, 3600, 3200}, 55)};
    const double h = 1e-3;
    const auto at = [&](double f, bool ease) {
        return cameraOnPath(keys, f, RenderCamera{}, ease).position;
    };
    // Eased: the speed leaving the first key and arriving at the last is zero (to the
    // difference's order, h times the acceleration).
    EXPECT_LT((at(300 + h, true) - at(300, true)).length() / h, 1.0);
    EXPECT_LT((at(491, true) - at(491 - h, true)).length() / h, 1.0);
    // Without: the camera leaves at the one-sided chord's speed, tens of metres a frame.
    EXPECT_GT((at(300 + h, false) - at(300, false)).length() / h, 30.0);
    for (const CameraKey& k : keys) EXPECT_EQ(at(k.frame, true), k.position);
    // The inner key keeps its Catmull-Rom tangent: the same velocity through it either way.
    const RenderVec3 eased = (at(400 + h, true) - at(400 - h, true)) * (0.5 / h);
    const RenderVec3 plain = (at(400 + h, false) - at(400 - h, false)) * (0.5 / h);
    EXPECT_LT((eased - plain).length(), 1e-3 * plain.length());
}

}  // namespace cg::algo
