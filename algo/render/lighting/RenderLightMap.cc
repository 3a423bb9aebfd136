#include "algo/render/lighting/RenderLightMap.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/render/media/TrilinearDensity.h"
#include "util/CheckedSize.h"

namespace cg::algo {

RenderLightMap::RenderLightMap(const openvdb::FloatGrid& grid, const RenderOccupancy& occupancy,
                               const RenderVec3& towardLight, double extinction, double texelVoxels,
                               double stepVoxels, std::size_t maxTexels,
                               const std::function<bool()>& cancelled)
{
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    if (active.empty() || occupancy.empty() || extinction <= 0.0) return;
    if (!(towardLight.length() > 0.0)) throw std::invalid_argument("light direction is zero");
    if (!(texelVoxels > 0.0) || !(stepVoxels > 0.0))
        throw std::invalid_argument("light-map texel and step must be positive");
    if (maxTexels < 16) throw std::invalid_argument("light-map budget below 16 texels");

    mW = towardLight.unitSafe();
    const RenderVec3 helper = std::abs(mW.z()) < 0.9 ? RenderVec3(0, 0, 1) : RenderVec3(1, 0, 0);
    mU = mW.cross(helper).unitSafe();
    mV = mW.cross(mU);

    // World extent of the region where trilinear samples can be non-zero, in the light basis.
    const openvdb::math::Transform& xform = grid.transform();
    const RenderVec3 lo = RenderVec3(active.min().asVec3d()) - RenderVec3(1.0);
    const RenderVec3 hi = RenderVec3(active.max().asVec3d()) + RenderVec3(1.0);
    double rmin[3] = {1e300, 1e300, 1e300}, rmax[3] = {-1e300, -1e300, -1e300};
    for (int c = 0; c < 8; ++c) {
        const RenderVec3 idx((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                             (c & 4) ? hi.z() : lo.z());
        const RenderVec3 w = xform.indexToWorld(idx);
        const double r[3] = {w.dot(mU), w.dot(mV), w.dot(mW)};
        for (int a = 0; a < 3; ++a) {
            rmin[a] = std::min(rmin[a], r[a]);
            rmax[a] = std::max(rmax[a], r[a]);
        }
    }
    mOrigin = mU * rmin[0] + mV * rmin[1] + mW * rmin[2];

    // Index-space images of the basis (the transform is affine): column points are
    // baseIdx + s * wIdx with s in metres along the light.
    const RenderVec3 originIdx = xform.worldToIndex(mOrigin);
    const RenderVec3 uIdx = xform.worldToIndex(mOrigin + mU) - originIdx;
    const RenderVec3 vIdx = xform.worldToIndex(mOrigin + mV) - originIdx;
    const RenderVec3 wIdx = xform.worldToIndex(mOrigin + mW) - originIdx;
    const auto columnBase = [&](std::size_t col) {
        const auto iu = static_cast<int>(col / static_cast<std::size_t>(mN[1]));
        const auto iv = static_cast<int>(col % static_cast<std::size_t>(mN[1]));
        return originIdx + uIdx * (iu * mH) + vIdx * (iv * mH);
    };

    // The texel: the finest, from texelVoxels up, whose columns and stored texels fit.
    const double voxel = xform.voxelSize().x();
    mH = texelVoxels * voxel;
    for (;; mH *= 1.25) {
        // Texels along each axis in doubles first: over voxels far apart, a fine texel's
        // count need not fit an int. Past maxTexels along an axis, the columns cannot fit
        // either (along the light, a column could hold no more).
        double along[3];
        for (int a = 0; a < 3; ++a) along[a] = std::ceil((rmax[a] - rmin[a]) / mH) + 1.0;
        if (!(std::max({along[0], along[1], along[2]}) <= double(maxTexels))) continue;
        for (int a = 0; a < 3; ++a) mN[a] = static_cast<int>(along[a]);
        const std::optional<std::uint64_t> fitting =
            util::productWithin({mN[0], mN[1]}, maxTexels / 4);
        if (!fitting) continue;
        const auto columns = static_cast<std::size_t>(*fitting);
        mColumns.assign(columns, Column{});
        const double length = mH * (mN[2] - 1);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, columns, 64),
                          [&](const tbb::blocked_range<std::size_t>& range) {
                              std::vector<RenderOccupancy::Span> spans;
                              for (std::size_t col = range.begin(); col != range.end(); ++col) {
                                  spans.clear();
                                  occupancy.spans(columnBase(col), wIdx, 0.0, length, spans);
                                  if (spans.empty()) continue;
                                  // τ(iw) is 0 from the node past the last span on, and
                                  // constant up to the node before the first.
                                  Column& c = mColumns[col];
                                  c.lo = std::max(0, static_cast<int>(spans.front().t0 / mH));
                                  c.hi = std::min(
                                      mN[2] - 1, static_cast<int>(std::ceil(spans.back().t1 / mH)));
                              }
                          });
        std::size_t stored = 0;
        for (Column& c : mColumns) {
            c.offset = stored;
            if (c.hi >= c.lo) stored += static_cast<std::size_t>(c.hi - c.lo + 1);
            if (stored > maxTexels) break;
        }
        if (stored <= maxTexels) {
            mTau.assign(stored, 0.0f);
            break;
        }
    }

    const int nSub = std::max(1, static_cast<int>(std::ceil(mH / (stepVoxels * voxel))));
    const double ds = mH / nSub;
    const double length = mH * (mN[2] - 1);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mColumns.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          if (cancelled && cancelled()) return;
                          TrilinearDensity density(grid, occupancy);
                          std::vector<RenderOccupancy::Span> spans;
                          for (std::size_t col = range.begin(); col != range.end(); ++col) {
                              const Column& c = mColumns[col];
                              if (c.hi < c.lo) continue;
                              const RenderVec3 base = columnBase(col);
                              spans.clear();
                              occupancy.spans(base, wIdx, 0.0, length, spans);
                              float* tau = mTau.data() + c.offset;  // tau[iw - lo]
                              // From the light end (τ(hi) = 0) down, one texel at a time.
                              double sum = 0.0;
                              std::size_t si =
                                  spans.size();  // spans are in increasing s; walk backwards
                              for (int iw = c.hi; iw > c.lo; --iw) {
                                  for (int k = 0; k < nSub; ++k) {
                                      const double s = iw * mH - (k + 0.5) * ds;
                                      while (si > 0 && spans[si - 1].t0 > s) --si;
                                      if (si == 0) break;
                                      if (s > spans[si - 1].t1) continue;
                                      const double d = density.sample(base + wIdx * s);
                                      if (d > 0.0) sum += extinction * d * ds;
                                  }
                                  tau[iw - 1 - c.lo] = static_cast<float>(sum);
                              }
                          }
                      });
}

double RenderLightMap::opticalDepth(const RenderVec3& p) const { return lookup(p, false); }

double RenderLightMap::columnDepth(const RenderVec3& p) const { return lookup(p, true); }

double RenderLightMap::lookup(const RenderVec3& p, bool farEnd) const
{
    if (mTau.empty()) return 0.0;
    const RenderVec3 rel = p - mOrigin;
    const double inv = 1.0 / mH;
    double f[3] = {rel.dot(mU) * inv, rel.dot(mV) * inv, farEnd ? 0.0 : rel.dot(mW) * inv};
    int i0[3];
    double w1[3];
    for (int a = 0; a < 3; ++a) {
        f[a] = std::clamp(f[a], 0.0, double(mN[a] - 1));
        i0[a] = std::min(static_cast<int>(f[a]), std::max(mN[a] - 2, 0));
        w1[a] = f[a] - i0[a];
    }
    // The four columns around p, each read once for its two nodes.
    double tau[2][2][2];  // [dw][dv][du]
    for (int dv = 0; dv < 2; ++dv)
        for (int du = 0; du < 2; ++du) {
            const Column& c = mColumns[static_cast<std::size_t>(std::min(i0[0] + du, mN[0] - 1)) *
                                           static_cast<std::size_t>(mN[1]) +
                                       static_cast<std::size_t>(std::min(i0[1] + dv, mN[1] - 1))];
            for (int dw = 0; dw < 2; ++dw)
                tau[dw][dv][du] = tauIn(c, std::min(i0[2] + dw, mN[2] - 1));
        }
    double result = 0.0;
    for (int c = 0; c < 8; ++c) {
        const int du = c & 1, dv = (c >> 1) & 1, dw = (c >> 2) & 1;
        const double w =
            (du ? w1[0] : 1.0 - w1[0]) * (dv ? w1[1] : 1.0 - w1[1]) * (dw ? w1[2] : 1.0 - w1[2]);
        if (w > 0.0) result += w * tau[dw][dv][du];
    }
    return result;
}

}  // namespace cg::algo
