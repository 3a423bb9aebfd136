#include "algo/render/SurfaceGather.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

constexpr int kUnits = GatherLattice::kUnits;
constexpr int kLanes = 1 + kUnits;  ///< per cell of a sweep: T, then E per unit

/// `count` (rounded up to even) unit vectors of a Fibonacci sphere: z = 1 − (2i + 1) / K,
/// azimuths a golden angle apart. None lies on the horizon.
std::vector<RenderVec3> fibonacciSphere(int count)
{
    const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
    count += count % 2;
    std::vector<RenderVec3> out;
    for (int i = 0; i < count; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / count;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return out;
}

class Sweep {
public:
    Sweep(const GatherLattice& lattice, std::vector<float>& field) : L(lattice), mField(field)
    {
        mStride[0] = static_cast<std::size_t>(L.n[1]) * static_cast<std::size_t>(L.n[2]);
        mStride[1] = static_cast<std::size_t>(L.n[2]);
        mStride[2] = 1;
    }

    /// Fills the field for the direction whose travel moves `u` cells a metre.
    void run(const RenderVec3& u)
    {
        mA = 0;
        for (int axis = 1; axis < 3; ++axis)
            if (std::abs(u[axis]) > std::abs(u[mA])) mA = axis;
        mB = (mA + 1) % 3;
        mC = (mA + 2) % 3;
        mStep = 1.0 / std::abs(u[mA]);
        mShift[0] = u[mB] * mStep;
        mShift[1] = u[mC] * mStep;
        const int s = u[mA] > 0.0 ? 1 : -1;
        for (int t = 0; t < L.n[mA]; ++t) {
            const int i = s > 0 ? L.n[mA] - 1 - t : t;
            tbb::parallel_for(0, L.n[mB], [&](int j) {
                for (int k = 0; k < L.n[mC]; ++k) fill(i, j, k, i + s);
            });
        }
    }

    /// T and E at (fractional) cell coordinates q, trilinear; clear and dark outside.
    void lookup(const RenderVec3& q, double (&out)[kLanes]) const
    {
        int base[3];
        double frac[3];
        for (int a = 0; a < 3; ++a) {
            const double f = std::floor(q[a]);
            base[a] = static_cast<int>(f);
            frac[a] = q[a] - f;
        }
        std::fill(out, out + kLanes, 0.0);
        for (int corner = 0; corner < 8; ++corner) {
            double w = 1.0;
            int at[3];
            for (int a = 0; a < 3; ++a) {
                const int bit = (corner >> a) & 1;
                at[a] = base[a] + bit;
                w *= bit ? frac[a] : 1.0 - frac[a];
            }
            if (w == 0.0) continue;
            if (!inside(at[0], at[1], at[2])) {
                out[0] += w;
                continue;
            }
            const float* cell = &mField[kLanes * L.cell(at[0], at[1], at[2])];
            for (int l = 0; l < kLanes; ++l) out[l] += w * cell[l];
        }
    }

    int dominantAxis() const { return mA; }

private:
    bool inside(int i, int j, int k) const
    {
        return i >= 0 && j >= 0 && k >= 0 && i < L.n[0] && j < L.n[1] && k < L.n[2];
    }
    /// (i, j, k) along the sweep's axes (a, b, c).
    std::size_t swept(int i, int j, int k) const
    {
        return static_cast<std::size_t>(i) * mStride[mA] +
               static_cast<std::size_t>(j) * mStride[mB] +
               static_cast<std::size_t>(k) * mStride[mC];
    }

    /// One cell from the slice upstream: the segment to it is optically τ = σ̄ Δs thick and
    /// glows with the extinction-weighted mean source of its two ends.
    void fill(int i, int j, int k, int upstream)
    {
        const std::size_t cell = swept(i, j, k);
        double up[kLanes] = {0.0, 0.0, 0.0, 0.0, 0.0};
        double sigmaUp = 0.0, glowUp[kUnits] = {0.0, 0.0, 0.0, 0.0};
        const bool slice = upstream >= 0 && upstream < L.n[mA];
        const double y = j + mShift[0], z = k + mShift[1];
        const int j0 = static_cast<int>(std::floor(y)), k0 = static_cast<int>(std::floor(z));
        const double fy = y - j0, fz = z - k0;
        for (int corner = 0; corner < 4; ++corner) {
            const int jj = j0 + (corner & 1), kk = k0 + (corner >> 1);
            const double w = ((corner & 1) ? fy : 1.0 - fy) * ((corner >> 1) ? fz : 1.0 - fz);
            if (w == 0.0) continue;
            if (!slice || jj < 0 || kk < 0 || jj >= L.n[mB] || kk >= L.n[mC]) {
                up[0] += w;
                continue;
            }
            const std::size_t other = swept(upstream, jj, kk);
            const float* lanes = &mField[kLanes * other];
            for (int l = 0; l < kLanes; ++l) up[l] += w * lanes[l];
            const double sigma = L.extinction[other];
            sigmaUp += w * sigma;
            for (int l = 0; l < kUnits; ++l) glowUp[l] += w * sigma * L.source[other][l];
        }
        const double sigmaHere = L.extinction[cell];
        const double sigmaSum = sigmaHere + sigmaUp;
        float* out = &mField[kLanes * cell];
        if (!(sigmaSum > 0.0)) {
            for (int l = 0; l < kLanes; ++l) out[l] = static_cast<float>(up[l]);
            return;
        }
        const double kept = std::exp(-0.5 * sigmaSum * mStep);
        out[0] = static_cast<float>(up[0] * kept);
        for (int l = 0; l < kUnits; ++l) {
            const double glow = (sigmaHere * L.source[cell][l] + glowUp[l]) / sigmaSum;
            out[1 + l] = static_cast<float>(up[1 + l] * kept + glow * (1.0 - kept));
        }
    }

    const GatherLattice& L;
    std::vector<float>& mField;
    std::size_t mStride[3];
    int mA = 0, mB = 1, mC = 2;
    double mStep = 1.0;             ///< m travelled from one slice to the next
    double mShift[2] = {0.0, 0.0};  ///< cells moved across (b, c) from one slice to the next
};

/// The lattice in blocks of stride^3 cells: mean extinction, extinction-weighted source.
GatherLattice coarsened(const GatherLattice& fine, int stride)
{
    GatherLattice out;
    for (int a = 0; a < 3; ++a) out.n[a] = (fine.n[a] + stride - 1) / stride;
    out.cellsPerMetre = fine.cellsPerMetre * (1.0 / stride);
    for (int f = 0; f < 6; ++f) out.normal[f] = fine.normal[f];
    out.extinction.assign(out.cells(), 0.0);
    out.source.assign(out.cells(), {0.0f, 0.0f, 0.0f, 0.0f});
    const double perCell = 1.0 / (double(stride) * stride * stride);
    tbb::parallel_for(0, out.n[0], [&](int I) {
        for (int J = 0; J < out.n[1]; ++J)
            for (int K = 0; K < out.n[2]; ++K) {
                double sigma = 0.0, glow[kUnits] = {0.0, 0.0, 0.0, 0.0};
                for (int i = I * stride; i < std::min(fine.n[0], (I + 1) * stride); ++i)
                    for (int j = J * stride; j < std::min(fine.n[1], (J + 1) * stride); ++j)
                        for (int k = K * stride; k < std::min(fine.n[2], (K + 1) * stride); ++k) {
                            const std::size_t c = fine.cell(i, j, k);
                            sigma += fine.extinction[c];
                            for (int l = 0; l < kUnits; ++l)
                                glow[l] += fine.extinction[c] * fine.source[c][l];
                        }
                const std::size_t c = out.cell(I, J, K);
                out.extinction[c] = sigma * perCell;
                if (sigma > 0.0)
                    for (int l = 0; l < kUnits; ++l)
                        out.source[c][l] = static_cast<float>(glow[l] / sigma);
            }
    });
    return out;
}

/// The gather on `lattice`, whose cells are `stride` cells of the faces' lattice.
std::vector<GatheredView> gatherOn(const GatherLattice& lattice,
                                   const std::vector<GatherFace>& faces, int directions,
                                   double clearance, int stride,
                                   const std::function<bool()>& cancelled)
{
    const std::size_t cells = lattice.cells();
    if (lattice.extinction.size() != cells || lattice.source.size() != cells)
        throw std::invalid_argument("gather lattice: fields do not match its size");
    const std::vector<RenderVec3> dirs = fibonacciSphere(std::max(2, directions));
    // Each face kind's cosine weights over the directions on each side of the horizon.
    double weight[6][2] = {};
    for (int kind = 0; kind < 6; ++kind)
        for (const RenderVec3& d : dirs) {
            const double c = d.dot(lattice.normal[kind]);
            if (c > 0.0) weight[kind][d.z() > 0.0 ? 0 : 1] += c;
        }

    std::vector<GatheredView> views(faces.size());
    for (GatheredView& v : views) v.transmittance[0] = v.transmittance[1] = 0.0;
    std::vector<float> field(kLanes * cells);
    Sweep sweep(lattice, field);
    for (const RenderVec3& d : dirs) {
        if (cancelled && cancelled()) break;
        const RenderVec3 u = lattice.cellsPerMetre * d;
        sweep.run(u);
        const double reach = clearance / std::abs(u[sweep.dominantAxis()]);
        const int side = d.z() > 0.0 ? 0 : 1;
        tbb::parallel_for(std::size_t(0), faces.size(), [&](std::size_t f) {
            const GatherFace& face = faces[f];
            const double c = d.dot(lattice.normal[face.kind]);
            if (!(c > 0.0)) return;
            double seen[kLanes];
            const RenderVec3 air(face.air[0], face.air[1], face.air[2]);
            sweep.lookup((air + RenderVec3(0.5)) / double(stride) - RenderVec3(0.5) + u * reach,
                         seen);
            GatheredView& v = views[f];
            v.transmittance[side] += c * seen[0];
            for (int l = 0; l < kUnits; ++l) v.emitted[side][l] += c * seen[1 + l];
        });
    }
    tbb::parallel_for(std::size_t(0), faces.size(), [&](std::size_t f) {
        GatheredView& v = views[f];
        for (int side = 0; side < 2; ++side) {
            const double w = weight[faces[f].kind][side];
            if (!(w > 0.0)) {
                v.transmittance[side] = 1.0;
                continue;
            }
            v.transmittance[side] /= w;
            for (int l = 0; l < kUnits; ++l) v.emitted[side][l] /= w;
        }
    });
    return views;
}

}  // namespace

std::vector<GatheredView> gatherSurfaceLight(const GatherLattice& lattice,
                                             const std::vector<GatherFace>& faces, int directions,
                                             double clearance, int stride,
                                             const std::function<bool()>& cancelled)
{
    if (stride > 1)
        return gatherOn(coarsened(lattice, stride), faces, directions, clearance, stride,
                        cancelled);
    return gatherOn(lattice, faces, directions, clearance, 1, cancelled);
}

}  // namespace cg::algo
