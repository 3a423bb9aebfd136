#include "algo/render/lighting/DiffuseLight.h"

#include <algorithm>
#include <cmath>

namespace cg::algo {

namespace {

constexpr double kMaxFluxRatio = 0.95;  ///< |F| / φ kept below 1, a fully collimated beam

}  // namespace

DiffuseLobe diffuseLobe(double phi, const RenderVec3& flux)
{
    DiffuseLobe out;
    if (!(phi > 0.0)) return out;
    out.scale = phi * kInvFourPi;
    // Both of its HG lobes need only k² and k cos θ = F·ω / φ: no |F| unless k is capped.
    const double squared = flux.lengthSqr(), cap = kMaxFluxRatio * phi;
    if (squared < cap * cap) {
        const double inverse = 1.0 / phi;
        out.k2 = squared * inverse * inverse;
        out.axis = flux * inverse;
    } else {
        out.k2 = kMaxFluxRatio * kMaxFluxRatio;
        out.axis = flux * (kMaxFluxRatio / std::sqrt(squared));
    }
    return out;
}

double diffuseScattered(const DiffuseLobe& lobe, const RenderVec3& toward,
                        const DeltaEddington& split)
{
    const double kc = lobe.axis.dot(toward);
    const auto hg = [&](double g) {  // HG(cos θ, g k) × 4π
        const double gg = g * g * lobe.k2, d = 1.0 + gg - 2.0 * g * kc;
        return (1.0 - gg) / (d * std::sqrt(d));
    };
    return lobe.scale * (split.peak * hg(1.0) + (1.0 - split.peak) * hg(split.g));
}

double diffuseScattered(double phi, const RenderVec3& flux, const RenderVec3& toward,
                        const DeltaEddington& split)
{
    return diffuseScattered(diffuseLobe(phi, flux), toward, split);
}

DiffuseLight::Sample DiffuseLight::at(const RenderVec3& p) const
{
    Sample out;
    for (int c = 0; c < 3; ++c) out.phi[c] = mOutside[c];
    if (mCells.empty()) return out;
    const RenderVec3 q = mXform.worldToIndex(p);
    const double half = 0.5 * (mVoxels - 1);
    double f[3] = {(q.x() - mFirstVoxel.x() - half) / mVoxels,
                   (q.y() - mFirstVoxel.y() - half) / mVoxels,
                   (q.z() - mFirstVoxel.z() - half) / mVoxels};
    int i0[3];
    for (int a = 0; a < 3; ++a) {
        if (!(f[a] >= 0.0) || f[a] >= mN[a] - 1) return out;
        i0[a] = static_cast<int>(f[a]);
        f[a] -= i0[a];
    }
    // The trilinear interpolant of every lane and its derivative along each axis, in float
    // over whole records (which the compiler turns into vector arithmetic).
    constexpr int kLanes = Cell::kLanes;
    const float w[3][2] = {{1.0f - float(f[0]), float(f[0])},
                           {1.0f - float(f[1]), float(f[1])},
                           {1.0f - float(f[2]), float(f[2])}};
    constexpr float kSlope[2] = {-1.0f, 1.0f};
    // Only the fluences' gradients are needed: 4 lanes (R, G, B and D, unused) in place of 8.
    constexpr int kGradientLanes = 4;
    float value[kLanes] = {}, dx[kGradientLanes] = {}, dy[kGradientLanes] = {},
          dz[kGradientLanes] = {};
    for (int corner = 0; corner < 8; ++corner) {
        const int a = corner & 1, b = (corner >> 1) & 1, c = (corner >> 2) & 1;
        const float weight = w[0][a] * w[1][b] * w[2][c];
        const float gx = kSlope[a] * w[1][b] * w[2][c];
        const float gy = w[0][a] * kSlope[b] * w[2][c];
        const float gz = w[0][a] * w[1][b] * kSlope[c];
        const float* lane = mCells[index(i0[0] + a, i0[1] + b, i0[2] + c)].lane;
        for (int k = 0; k < kLanes; ++k) value[k] += weight * lane[k];
        for (int k = 0; k < kGradientLanes; ++k) {
            dx[k] += gx * lane[k];
            dy[k] += gy * lane[k];
            dz[k] += gz * lane[k];
        }
    }
    // World gradients: cell coordinates are index coordinates / mVoxels; the transform's
    // inverse Jacobian transpose takes an index-space gradient to world space.
    const double D = value[Cell::D];
    const RenderVec3 drift(value[Cell::DriftX], value[Cell::DriftY], value[Cell::DriftZ]);
    for (int c = 0; c < 3; ++c) {
        out.phi[c] = value[c];
        const openvdb::Vec3d grad(dx[c], dy[c], dz[c]);
        out.flux[c] = (mGradientToWorld * (grad / double(mVoxels))) * -D + drift * mSun[c];
    }
    return out;
}

RenderVec3 DiffuseLight::groundAmbient(const RenderVec3& p, const RenderVec3& open) const
{
    std::size_t at[4];
    double weight[4];
    if (mGroundRadiance.empty() || !mGround.corners(p, at, weight)) return open;
    RenderVec3 sum(0.0);
    for (int c = 0; c < 4; ++c) sum += mGroundRadiance[at[c]] * weight[c];
    return sum;
}

}  // namespace cg::algo
