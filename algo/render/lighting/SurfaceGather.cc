#include "algo/render/lighting/SurfaceGather.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/render/RenderRays.h"
#include "algo/render/lighting/DiffuseLight.h"

namespace cg::algo {

namespace {

constexpr int kUnits = GatherLattice::kUnits;
constexpr int kLanes = 1 + kUnits;  ///< per cell of a sweep: T, then E per unit
/// The sideways blur's weight a per slice (Sweep::spread), our choice: against the path
/// tracer on Figure 9 it gives less error than no blur at every turn of the directions, and
/// as little as two or four such blurs a slice (docs/notes/code-history.md); it spreads a
/// sweep √(0.6 s) blocks after s slices, as wide as a 32-direction cone (half-angle 0.36 rad)
/// at about 20 blocks.
constexpr double kSpreadPerSlice = 0.3;

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

/// The lattice the sweeps run on, in blocks of stride^3 cells of the gather's lattice:
/// dense, each block with the extinction-weighted means of its cloud cells.
struct Blocks : CellBox {
    static constexpr int kMoments = kUnits * 4;  ///< per unit: φ, then F (x, y, z)
    openvdb::Mat3d cellsPerMetre = openvdb::Mat3d::identity();
    RenderVec3 origin{0.0};
    std::vector<double> extinction;  ///< mean σ_t, 1/m (0: clear air)
    std::vector<float> beam;
    /// Per unit, the lobe of its diffuse light, from the extinction-weighted means of φ and F.
    std::vector<std::array<DiffuseLobe, kUnits>> lobes;
    /// J per unit light toward the current sweep's −v, radiance.
    std::vector<std::array<float, kUnits>> source;
};

/// Cells of a slice per parallel task, at least (our choice): a sweep is thousands of
/// slices a frame, and a small lattice's (Figure 6's: under a thousand blocks) shared out a
/// row per task spends more on the tasks than on the cells. 256 renders the frame of
/// bench/render_bench.cc faster than larger grains or a row a task (timings in
/// docs/notes/code-history.md).
constexpr int kCellsPerTask = 256;

/// fn(begin, end) over `rows` rows of `length` cells, at least kCellsPerTask cells a task;
/// on the calling thread alone, without the scheduler, when there are not two tasks' worth
/// (the early frames of a run: thousands of slices of a few hundred cells a frame).
template <class Fn>
void forRows(int rows, int length, Fn&& fn)
{
    const int grain = std::max(1, kCellsPerTask / std::max(1, length));
    if (rows < 2 * grain) {
        fn(0, rows);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, rows, grain),
                      [&](const tbb::blocked_range<int>& r) { fn(r.begin(), r.end()); });
}

class Sweep {
public:
    Sweep(const Blocks& lattice, std::vector<float>& field) : L(lattice), mField(field)
    {
        mStride[0] = static_cast<std::size_t>(L.n[1]) * static_cast<std::size_t>(L.n[2]);
        mStride[1] = static_cast<std::size_t>(L.n[2]);
        mStride[2] = 1;
        // The lattice axis nearest the vertical: the spread keeps to the others.
        const openvdb::Mat3d metresPerCell = L.cellsPerMetre.inverse();
        double most = -1.0;
        for (int a = 0; a < 3; ++a) {
            RenderVec3 axis(0.0);
            axis[a] = 1.0;
            const RenderVec3 step = metresPerCell * axis;
            const double up = std::abs(step.z()) / step.length();
            if (up > most) {
                most = up;
                mVertical = a;
            }
        }
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
        // The upstream point of every cell of a slice lies the same fraction of a cell away
        // from a cell of the slice before: its four cells and their weights are shared.
        double fraction[2];
        for (int a = 0; a < 2; ++a) {
            const double whole = std::floor(mShift[a]);
            mOffset[a] = static_cast<int>(whole);
            fraction[a] = mShift[a] - whole;
        }
        for (int corner = 0; corner < 4; ++corner) {
            const int b = corner & 1, c = corner >> 1;
            mWeight[corner] =
                (b ? fraction[0] : 1.0 - fraction[0]) * (c ? fraction[1] : 1.0 - fraction[1]);
            mCorner[corner] = (b ? mStride[mB] : 0) + (c ? mStride[mC] : 0);
        }
        const int s = u[mA] > 0.0 ? 1 : -1;
        // Cells in memory order within a slice where one of its axes is the lattice's last.
        const bool alongB = mStride[mB] < mStride[mC];
        const int outer = L.n[alongB ? mC : mB], inner = L.n[alongB ? mB : mC];
        for (int t = 0; t < L.n[mA]; ++t) {
            const int i = s > 0 ? L.n[mA] - 1 - t : t;
            forRows(outer, inner, [&](int begin, int end) {
                for (int o = begin; o != end; ++o)
                    for (int n = 0; n < inner; ++n)
                        alongB ? fill(i, n, o, i + s) : fill(i, o, n, i + s);
            });
            spread(i);
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
        // All eight corners inside, as mostly: their offsets from the first, unchecked.
        const bool allInside =
            inside(base[0], base[1], base[2]) && inside(base[0] + 1, base[1] + 1, base[2] + 1);
        const std::size_t first = allInside ? L.cell(base[0], base[1], base[2]) : 0;
        for (int corner = 0; corner < 8; ++corner) {
            double w = 1.0;
            int at[3];
            std::size_t offset = 0;
            for (int a = 0; a < 3; ++a) {
                const int bit = (corner >> a) & 1;
                at[a] = base[a] + bit;
                w *= bit ? frac[a] : 1.0 - frac[a];
                offset += bit ? mStride[a] : 0;
            }
            if (w == 0.0) continue;
            if (!allInside && !inside(at[0], at[1], at[2])) {
                out[0] += w;
                continue;
            }
            const float* cell =
                &mField[kLanes * (allInside ? first + offset : L.cell(at[0], at[1], at[2]))];
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

    /// Blurs slice i sideways, [a, 1 − 2a, a] along each of its horizontal axes (edge cells
    /// repeated), before the next slice reads it. A direction of the sweep stands for a
    /// cone of 4π / N steradians, not a ray: without the spread a neighbouring cloud that
    /// lies between two directions' azimuths is missed by both, and one that a direction
    /// meets counts for the whole cone, so the light a face gathers hangs on where the
    /// directions happen to fall (Figure 9's error changes with a turn of the directions
    /// about z). The blur widens each sweep with distance as a cone does, if only
    /// as √distance. It keeps to the horizontal: across heights it would carry shade and
    /// glow from above the horizon to below it (a slab overhead would dim the view down).
    void spread(int i)
    {
        for (const int axis : {mB, mC})
            if (axis != mVertical) spreadAlong(i, axis == mB);
    }

    /// The blur of slice i along b (or along c), line by line in parallel: each line of
    /// cells along that axis is blurred from a copy of itself (one copy buffer a chunk).
    void spreadAlong(int i, bool alongB)
    {
        const int length = L.n[alongB ? mB : mC], lines = L.n[alongB ? mC : mB];
        constexpr float a = static_cast<float>(kSpreadPerSlice), keep = 1.0f - 2.0f * a;
        forRows(lines, length, [&](int begin, int end) {
            std::vector<float> copy(kLanes * static_cast<std::size_t>(length));
            for (int line = begin; line != end; ++line) {
                const auto at = [&](int x) {
                    return &mField[kLanes * (alongB ? swept(i, x, line) : swept(i, line, x))];
                };
                for (int x = 0; x < length; ++x) std::copy_n(at(x), kLanes, &copy[kLanes * x]);
                for (int x = 0; x < length; ++x) {
                    const float* m = &copy[kLanes * std::max(0, x - 1)];
                    const float* c = &copy[kLanes * x];
                    const float* p = &copy[kLanes * std::min(length - 1, x + 1)];
                    float* out = at(x);
                    for (int l = 0; l < kLanes; ++l) out[l] = keep * c[l] + a * (m[l] + p[l]);
                }
            }
        });
    }

    /// One cell from the slice upstream: the segment to it is optically τ = σ̄ Δs thick and
    /// glows with the extinction-weighted mean source of its two ends.
    void fill(int i, int j, int k, int upstream)
    {
        const std::size_t cell = swept(i, j, k);
        double up[kLanes] = {0.0, 0.0, 0.0, 0.0, 0.0};
        double sigmaUp = 0.0, glowUp[kUnits] = {0.0, 0.0, 0.0, 0.0};
        const bool slice = upstream >= 0 && upstream < L.n[mA];
        const int j0 = j + mOffset[0], k0 = k + mOffset[1];
        const bool inside = slice && j0 >= 0 && k0 >= 0 && j0 + 1 < L.n[mB] && k0 + 1 < L.n[mC];
        const std::size_t first = inside ? swept(upstream, j0, k0) : 0;
        for (int corner = 0; corner < 4; ++corner) {
            const double w = mWeight[corner];
            if (w == 0.0) continue;
            std::size_t other = first + mCorner[corner];
            if (!inside) {
                const int jj = j0 + (corner & 1), kk = k0 + (corner >> 1);
                if (!slice || jj < 0 || kk < 0 || jj >= L.n[mB] || kk >= L.n[mC]) {
                    up[0] += w;
                    continue;
                }
                other = swept(upstream, jj, kk);
            }
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

    const Blocks& L;
    std::vector<float>& mField;
    std::size_t mStride[3];
    int mA = 0, mB = 1, mC = 2;
    int mVertical = 2;              ///< the lattice axis nearest the world's z
    double mStep = 1.0;             ///< m travelled from one slice to the next
    double mShift[2] = {0.0, 0.0};  ///< cells moved across (b, c) from one slice to the next
    int mOffset[2] = {0, 0};        ///< mShift's whole cells
    double mWeight[4] = {};         ///< bilinear, of the four upstream cells (b, c bits)
    std::size_t mCorner[4] = {};    ///< their offsets in the field from the first
};

/// The lattice's clouds in blocks of stride^3 cells: mean extinction, extinction-weighted
/// light.
Blocks blocksOf(const GatherLattice& fine, int stride)
{
    Blocks out;
    for (int a = 0; a < 3; ++a) out.n[a] = (fine.n[a] + stride - 1) / stride;
    out.cellsPerMetre = fine.cellsPerMetre * (1.0 / stride);
    out.origin = fine.origin + fine.cellsPerMetre.inverse() * RenderVec3(0.5 * (stride - 1));
    const std::size_t cells = out.cells();
    out.extinction.assign(cells, 0.0);
    out.beam.assign(cells, 0.0f);
    out.lobes.assign(cells, {});
    out.source.assign(cells, {0.0f, 0.0f, 0.0f, 0.0f});
    std::vector<std::array<double, 1 + Blocks::kMoments>> sum(cells);  // beam, then moments
    for (auto& s : sum) s.fill(0.0);
    const std::size_t planeStride = static_cast<std::size_t>(fine.n[1]) * fine.n[2];
    for (const GatherLattice::Cloud& c : fine.clouds) {
        if (c.cell >= fine.cells())
            throw std::invalid_argument("gather lattice: a cloud cell outside the lattice");
        const int i = static_cast<int>(c.cell / planeStride);
        const int j = static_cast<int>((c.cell / fine.n[2]) % fine.n[1]);
        const int k = static_cast<int>(c.cell % fine.n[2]);
        const std::size_t block = out.cell(i / stride, j / stride, k / stride);
        const double w = c.extinction;
        out.extinction[block] += w;
        std::array<double, 1 + Blocks::kMoments>& s = sum[block];
        s[0] += w * c.beam;
        for (int l = 0; l < kUnits; ++l) {
            s[1 + 4 * l] += w * c.phi[l];
            for (int a = 0; a < 3; ++a) s[2 + 4 * l + a] += w * c.flux[l][a];
        }
    }
    const double perCell = 1.0 / (double(stride) * stride * stride);
    for (std::size_t b = 0; b < cells; ++b) {
        const double sigma = out.extinction[b];
        if (!(sigma > 0.0)) continue;
        out.beam[b] = static_cast<float>(sum[b][0] / sigma);
        for (int l = 0; l < kUnits; ++l) {
            const double* m = &sum[b][1 + 4 * l];
            out.lobes[b][l] = diffuseLobe(m[0] / sigma, RenderVec3(m[1], m[2], m[3]) / sigma);
        }
        out.extinction[b] = sigma * perCell;
    }
    return out;
}

/// Each block's source radiance toward −v (v the direction looked along), per unit light.
void sourcesToward(const GatherLattice& lattice, Blocks& blocks, const RenderVec3& v)
{
    const RenderVec3 toward = -v;
    const double beamLobe = henyeyGreenstein(lattice.travel.dot(toward), lattice.split.g);
    tbb::parallel_for(std::size_t(0), blocks.cells(), [&](std::size_t b) {
        if (!(blocks.extinction[b] > 0.0)) return;
        for (int l = 0; l < kUnits; ++l)
            blocks.source[b][l] = static_cast<float>(
                lattice.albedo * diffuseScattered(blocks.lobes[b][l], toward, lattice.split));
        blocks.source[b][0] += static_cast<float>(blocks.beam[b] * beamLobe);
    });
}

/// What the ground sends back at point p (on z = 0) per ground unit: its map point's view of
/// the sky and the clouds' glow (bilinear; the open sky beyond the map) and its sun light.
void groundSends(const GatherGround& ground, const std::vector<GroundView>& map,
                 const RenderVec3& p, double (&out)[GatheredView::kGroundUnits])
{
    std::fill(out, out + GatheredView::kGroundUnits, 0.0);
    out[GatheredView::SkyLit] = 1.0;
    std::size_t at[4];
    double weight[4];
    if (ground.map.corners(p, at, weight)) {
        out[GatheredView::SkyLit] = 0.0;
        for (int c = 0; c < 4; ++c) {
            const GroundView& v = map[at[c]];
            out[GatheredView::SkyLit] += weight[c] * v.sky;
            for (int l = 0; l < kUnits; ++l)
                out[GatheredView::Glow + l] += weight[c] * v.emitted[l];
        }
    }
    if (ground.sunlit) out[GatheredView::SunLit] = ground.sunlit(p);
}

/// Box-blurs the map's views `radius` points each way, along x then y, twice (about a
/// Gaussian); near the map's edge over the points there are.
void smooth(const GroundGrid& map, int radius, std::vector<GroundView>& views)
{
    if (radius < 1 || views.empty()) return;
    const auto pass = [&](int axis) {
        const int along = map.n[axis], across = map.n[1 - axis];
        const std::size_t step = axis == 0 ? 1 : static_cast<std::size_t>(map.n[0]);
        const std::size_t rowStep = axis == 0 ? static_cast<std::size_t>(map.n[0]) : 1;
        std::vector<GroundView> in = views;
        tbb::parallel_for(0, across, [&](int row) {
            const std::size_t first = static_cast<std::size_t>(row) * rowStep;
            for (int i = 0; i < along; ++i) {
                GroundView sum{0.0, {0.0, 0.0, 0.0, 0.0}};
                const int lo = std::max(0, i - radius), hi = std::min(along - 1, i + radius);
                for (int k = lo; k <= hi; ++k) {
                    const GroundView& v = in[first + static_cast<std::size_t>(k) * step];
                    sum.sky += v.sky;
                    for (int l = 0; l < kUnits; ++l) sum.emitted[l] += v.emitted[l];
                }
                const double w = 1.0 / (hi - lo + 1);
                GroundView& out = views[first + static_cast<std::size_t>(i) * step];
                out.sky = sum.sky * w;
                for (int l = 0; l < kUnits; ++l) out.emitted[l] = sum.emitted[l] * w;
            }
        });
    };
    for (int repeat = 0; repeat < 2; ++repeat) {
        pass(0);
        pass(1);
    }
}

/// The parameter t at which the ray q + t u (cell coordinates) enters the lattice's box of
/// cells, or a negative number if it misses it (0 if q is inside).
double entering(const Blocks& lattice, const RenderVec3& q, const RenderVec3& u)
{
    const double lo[3] = {-0.5, -0.5, -0.5};
    const double hi[3] = {lattice.n[0] - 0.5, lattice.n[1] - 0.5, lattice.n[2] - 0.5};
    double near = 0.0, far = std::numeric_limits<double>::infinity();
    return clipToBox(q, u, lo, hi, near, far) ? near : -1.0;
}

/// Each face kind's cosine weights over the directions on each side of the horizon, and the
/// ground's over those above it: what the views' sums are divided by.
struct DirectionWeights {
    double face[6][2] = {};
    double ground = 0.0;
};

DirectionWeights weightsOver(const std::vector<RenderVec3>& dirs, const RenderVec3 (&normal)[6])
{
    DirectionWeights out;
    for (int kind = 0; kind < 6; ++kind)
        for (const RenderVec3& d : dirs) {
            const double c = d.dot(normal[kind]);
            if (c > 0.0) out.face[kind][d.z() > 0.0 ? 0 : 1] += c;
        }
    for (const RenderVec3& d : dirs) out.ground += std::max(0.0, d.z());
    return out;
}

/// A gather's faces and ground points and what each has seen so far, summed direction by
/// direction. The faces are taken by the air cell they open onto: what a direction's lookup
/// reads, and the ground point it reaches, depend on the air cell alone, so its faces share
/// them. Their views are summed in that order and put back in the faces' order at the end.
class Gather {
public:
    Gather(const GatherLattice& fine, Blocks& lattice, const std::vector<GatherFace>& faces,
           const GatherGround& ground, int stride);

    void finishGroundMap(double weight);
    void look(const RenderVec3& d, double clearance);
    Gathered result(const double (&weight)[6][2]);

private:
    struct Air {
        std::size_t first = 0;  ///< its first face in mByAir
        unsigned kinds = 0;     ///< bit k: it has a face of kind k
        RenderVec3 at{0.0};     ///< its centre in the swept lattice's cells
    };

    void groupByAir(const std::vector<GatherFace>& faces, int stride);
    void groundLooksUp(const RenderVec3& d, const RenderVec3& u);
    void facesLook(const RenderVec3& d, const RenderVec3& u, double reach);

    const GatherLattice& mFine;
    Blocks& mLattice;
    const GatherGround& mGround;
    const openvdb::Mat3d mMetresPerCell;
    std::vector<GroundView> mGroundViews;  ///< per point of the ground's map
    std::vector<std::size_t> mByAir;       ///< the faces in the order of their air cells
    std::vector<Air> mAirs;
    std::vector<int> mKindOf;          ///< per face in mByAir, its kind
    std::vector<GatheredView> mViews;  ///< per face in mByAir, its sums
    std::vector<float> mField;
    Sweep mSweep;
};

Gather::Gather(const GatherLattice& fine, Blocks& lattice, const std::vector<GatherFace>& faces,
               const GatherGround& ground, int stride)
    : mFine(fine),
      mLattice(lattice),
      mGround(ground),
      mMetresPerCell(lattice.cellsPerMetre.inverse()),
      mField(kLanes * lattice.cells()),
      mSweep(lattice, mField)
{
    if (ground.present)
        mGroundViews.assign(ground.map.points(), GroundView{0.0, {0.0, 0.0, 0.0, 0.0}});
    groupByAir(faces, stride);
}

void Gather::groupByAir(const std::vector<GatherFace>& faces, int stride)
{
    mByAir.resize(faces.size());
    std::iota(mByAir.begin(), mByAir.end(), std::size_t(0));
    const auto airOf = [&](std::size_t f) {
        const std::array<int, 3>& a = faces[f].air;
        return mFine.cell(a[0], a[1], a[2]);
    };
    std::stable_sort(mByAir.begin(), mByAir.end(),
                     [&](std::size_t x, std::size_t y) { return airOf(x) < airOf(y); });
    for (std::size_t i = 0; i < mByAir.size(); ++i) {
        const GatherFace& face = faces[mByAir[i]];
        if (i == 0 || airOf(mByAir[i]) != airOf(mByAir[i - 1])) {
            Air air;
            air.first = i;
            air.at = (RenderVec3(face.air[0], face.air[1], face.air[2]) + RenderVec3(0.5)) /
                         double(stride) -
                     RenderVec3(0.5);
            mAirs.push_back(air);
        }
        mAirs.back().kinds |= 1u << face.kind;
    }
    mKindOf.resize(mByAir.size());
    for (std::size_t i = 0; i < mByAir.size(); ++i) mKindOf[i] = faces[mByAir[i]].kind;
    mViews.resize(mByAir.size());
    for (GatheredView& v : mViews) v.transmittance[0] = v.transmittance[1] = 0.0;
}

/// Turns the ground points' sums over the directions above the horizon into means and blurs
/// the map: it is complete before a face looks down at it.
void Gather::finishGroundMap(double weight)
{
    for (GroundView& g : mGroundViews) {
        g.sky /= weight;
        for (double& e : g.emitted) e /= weight;
    }
    smooth(mGround.map, static_cast<int>(mGround.smoothing / mGround.map.spacing), mGroundViews);
}

/// Sweeps the lattice along d and adds what is seen along it: by the ground points (d above
/// the horizon) and by the faces that face d, from `clearance` swept cells out.
void Gather::look(const RenderVec3& d, double clearance)
{
    const int side = d.z() > 0.0 ? 0 : 1;
    const RenderVec3 u = mLattice.cellsPerMetre * d;
    sourcesToward(mFine, mLattice, d);
    mSweep.run(u);
    if (side == 0) groundLooksUp(d, u);
    facesLook(d, u, clearance / std::abs(u[mSweep.dominantAxis()]));
}

/// Each ground point looks up along d, into the lattice where it meets it.
void Gather::groundLooksUp(const RenderVec3& d, const RenderVec3& u)
{
    tbb::parallel_for(std::size_t(0), mGroundViews.size(), [&](std::size_t at) {
        const RenderVec3 q = mLattice.cellsPerMetre * (mGround.map.point(at) - mLattice.origin);
        const double t = entering(mLattice, q, u);
        GroundView& g = mGroundViews[at];
        if (t < 0.0) {
            g.sky += d.z();
            return;
        }
        RenderVec3 in = q + u * t;
        for (int a = 0; a < 3; ++a) in[a] = std::clamp(in[a], 0.0, mLattice.n[a] - 1.0);
        double seen[kLanes];
        mSweep.lookup(in, seen);
        g.sky += d.z() * seen[0];
        for (int l = 0; l < kUnits; ++l) g.emitted[l] += d.z() * seen[1 + l];
    });
}

/// Each air cell looks along d, `reach` metres out; each of its faces that faces d adds what
/// it sees, cosine-weighted, on d's side of the horizon, and below it the ground's light.
void Gather::facesLook(const RenderVec3& d, const RenderVec3& u, double reach)
{
    const int side = d.z() > 0.0 ? 0 : 1;
    double facing[6];
    unsigned facingKinds = 0;
    for (int kind = 0; kind < 6; ++kind) {
        facing[kind] = d.dot(mFine.normal[kind]);
        if (facing[kind] > 0.0) facingKinds |= 1u << kind;
    }
    const bool toGround = side == 1 && mGround.present;
    tbb::parallel_for(std::size_t(0), mAirs.size(), [&](std::size_t a) {
        const Air& air = mAirs[a];
        if (!(air.kinds & facingKinds)) return;
        double seen[kLanes];
        mSweep.lookup(air.at + u * reach, seen);
        // Below the horizon, the ground point this direction reaches and what it sends back.
        double sends[GatheredView::kGroundUnits];
        if (toGround) {
            const RenderVec3 from = mLattice.origin + mMetresPerCell * air.at;
            const double down = std::max(0.0, from.z()) / -d.z();
            groundSends(mGround, mGroundViews,
                        RenderVec3(from.x() + d.x() * down, from.y() + d.y() * down, 0.0), sends);
        }
        const std::size_t end = a + 1 < mAirs.size() ? mAirs[a + 1].first : mByAir.size();
        for (std::size_t i = air.first; i < end; ++i) {
            const double c = facing[mKindOf[i]];
            if (!(c > 0.0)) continue;
            GatheredView& v = mViews[i];
            v.transmittance[side] += c * seen[0];
            for (int l = 0; l < kUnits; ++l) v.emitted[side][l] += c * seen[1 + l];
            if (toGround)
                for (int g = 0; g < GatheredView::kGroundUnits; ++g)
                    v.ground[g] += c * seen[0] * sends[g];
        }
    });
}

/// The faces' means over their hemispheres, in the faces' order, and the ground's map; once,
/// at the end.
Gathered Gather::result(const double (&weight)[6][2])
{
    Gathered out;
    out.ground = std::move(mGroundViews);
    out.faces.resize(mByAir.size());
    tbb::parallel_for(std::size_t(0), mByAir.size(), [&](std::size_t i) {
        GatheredView& v = out.faces[mByAir[i]];
        v = mViews[i];
        for (int side = 0; side < 2; ++side) {
            const double w = weight[mKindOf[i]][side];
            if (!(w > 0.0)) {
                v.transmittance[side] = 1.0;
                continue;
            }
            v.transmittance[side] /= w;
            for (int l = 0; l < kUnits; ++l) v.emitted[side][l] /= w;
            if (side == 1)
                for (double& g : v.ground) g /= w;
        }
    });
    return out;
}

/// The gather on the lattice's blocks of `stride` cells.
Gathered gatherOn(const GatherLattice& fine, Blocks& lattice, const std::vector<GatherFace>& faces,
                  const GatherGround& ground, int directions, double clearance, int stride,
                  const std::function<bool()>& cancelled)
{
    // Directions above the horizon first: the ground's map is complete before a face looks
    // down at it.
    const std::vector<RenderVec3> dirs = fibonacciSphere(std::max(2, directions));
    const DirectionWeights weights = weightsOver(dirs, fine.normal);
    Gather gather(fine, lattice, faces, ground, stride);
    bool mapDone = false;
    for (const RenderVec3& d : dirs) {
        if (cancelled && cancelled()) break;
        if (!(d.z() > 0.0) && !mapDone) {
            gather.finishGroundMap(weights.ground);
            mapDone = true;
        }
        gather.look(d, clearance);
    }
    return gather.result(weights.face);
}

}  // namespace

Gathered gatherSurfaceLight(const GatherLattice& lattice, const std::vector<GatherFace>& faces,
                            const GatherGround& ground, int directions, double clearance,
                            int stride, const std::function<bool()>& cancelled)
{
    stride = std::max(1, stride);
    Blocks blocks = blocksOf(lattice, stride);
    return gatherOn(lattice, blocks, faces, ground, directions, clearance, stride, cancelled);
}

}  // namespace cg::algo
