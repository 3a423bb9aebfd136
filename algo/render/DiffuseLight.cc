#include "algo/render/DiffuseLight.h"

namespace cg::algo {

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
    double phi[3] = {0.0, 0.0, 0.0}, D = 0.0;
    openvdb::Vec3d grad[3];  // in cell coordinates
    for (auto& g : grad) g = openvdb::Vec3d(0.0);
    RenderVec3 drift(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        const int d[3] = {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1};
        double w = 1.0, dw[3] = {1.0, 1.0, 1.0};
        for (int a = 0; a < 3; ++a) {
            const double wa = d[a] ? f[a] : 1.0 - f[a];
            w *= wa;
            for (int b = 0; b < 3; ++b) dw[b] *= (a == b) ? (d[a] ? 1.0 : -1.0) : wa;
        }
        const Cell& cell = mCells[index(i0[0] + d[0], i0[1] + d[1], i0[2] + d[2])];
        D += w * cell.D;
        for (int a = 0; a < 3; ++a) drift[a] += w * cell.drift[a];
        for (int c = 0; c < 3; ++c) {
            phi[c] += w * cell.phi[c];
            for (int a = 0; a < 3; ++a) grad[c][a] += dw[a] * cell.phi[c];
        }
    }
    // World gradients: cell coordinates are index coordinates / mVoxels; the transform's
    // inverse Jacobian transpose takes an index-space gradient to world space.
    for (int c = 0; c < 3; ++c) {
        out.phi[c] = phi[c];
        out.flux[c] = (mGradientToWorld * (grad[c] / double(mVoxels))) * -D + drift * mSun[c];
    }
    return out;
}

}  // namespace cg::algo
