#pragma once
/// The Renderer's pinhole camera in the forms other tools read:
///
///  - OpenEXR's standard `worldToCamera` and `worldToNDC` attributes (RenderMan's
///    conventions, row vectors multiplied on the left, p' = p M): camera space is left-handed
///    with x right, y up and z along the view; NDC has (0, 0) at the image's top-left corner
///    and (1, 1) at its bottom-right, after dividing by w. World space is CloudGraph's (metres,
///    z up), the VDBs' space.
///  - Nuke's camera (what a `.chan` file holds): a y-up world, so CloudGraph's (x, y, z) is
///    Nuke's (x, z, -y); the camera looks down its local -z with y up; rotations in degrees
///    applied in the order Z, X, Y (Nuke's default ZXY: R = Ry Rx Rz); the vertical field of
///    view in degrees. Blender's bundled Nuke .chan importer reads it with "Make Z up" and
///    rotation order ZXY.
///
/// No engine includes.

#include <array>

#include "algo/render/CameraPath.h"
#include "algo/render/RenderSettings.h"

namespace cg::algo {

/// Row-major 4 x 4, for row vectors: p' = p M.
using Matrix44 = std::array<std::array<double, 4>, 4>;

Matrix44 worldToCamera(const RenderCamera& camera);
Matrix44 worldToNdc(const RenderCamera& camera);

/// Where a worldToNdc matrix puts world point `p` (in front of the camera): x right, y down,
/// the image in [0, 1]^2.
void projectToNdc(const Matrix44& worldToNdcMatrix, const RenderVec3& p, double ndc[2]);

struct NukePose {
    RenderVec3 translate;      ///< Nuke world (y up), m
    RenderVec3 rotateDegrees;  ///< about x, y, z; applied z first, then x, then y
    double verticalFovDegrees = 40.0;
};

NukePose nukePose(const RenderCamera& camera);

/// The camera key a Nuke pose stands for at `frame`: its look-at point 1 km along the view,
/// its up the camera's own (so a roll survives).
CameraKey keyFromNukePose(double frame, const NukePose& pose);

}  // namespace cg::algo
