#include "algo/render/lighting/RenderDiffusion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/render/lighting/ConjugateGradient.h"
#include "algo/render/lighting/SurfaceGather.h"
#include "algo/render/media/Phase.h"
#include "util/CheckedSize.h"

namespace cg::algo {

namespace {

constexpr std::size_t kMaxCells = std::size_t(1) << 21;

constexpr std::size_t kVoxelBatch = std::size_t(1) << 18;  ///< voxels shared out at a time
constexpr int kMaxIterations = 400;
constexpr int kLimiterPasses = 3;    ///< solves of the sun with the flux limiter updated
constexpr double kMostLimit = 4.0;   ///< the limiter's largest R, per cell width
constexpr double kTolerance = 1e-3;  ///< relative residual at which the solve stops
/// The same for the solves before the last (the flux limiter's, and the first solve of all
/// lights, which only feeds the gather): R and the clouds' glow need not be exact.
constexpr double kLimiterTolerance = 1e-2;
/// The same for the solve after a gather other than the last, which only feeds the next
/// gather (our choice): so loose a solve leaves the error against the path tracer as it is
/// and costs less. The limiter's solves need their kLimiterTolerance: looser, Figure 6's
/// error grows (docs/notes/code-history.md has the figures).
constexpr double kFeedTolerance = 0.1;
/// The gather (SurfaceGather.h), our choices, each the one with the least error against the
/// path tracer (docs/rendering.md; the figures in docs/notes/code-history.md): blocks of 2^3
/// cells give the error of the cells themselves at a fifth of the cost. It is read 4 blocks
/// (8 cells) out along each direction, nearer or farther being worse, and run twice, each
/// time followed by a solve of every light, so that the clouds' light a face sees comes from
/// clouds that already lit and shaded one another; a third gather changes little. The last
/// gather's directions decide how well a face sees a neighbouring cloud: from 80 on, more
/// directions, or the same turned about z, give the same error. The first gather only feeds
/// the second's clouds, so it runs on blocks of 4^3 cells read 2 blocks out (the same reach;
/// an eighth of the blocks to sweep) along 16 directions; fewer directions or finer blocks
/// are no better.
constexpr int kGatherDirections = 80;
constexpr int kGatherStride = 2;
constexpr double kGatherClearance = 4.0;
constexpr int kFirstGatherDirections = 16;
constexpr int kFirstGatherStride = 4;
constexpr double kFirstGatherClearance = 2.0;
constexpr int kGatherPasses = 2;
constexpr double kPi = 3.14159265358979323846;
/// The ground's map (our choice): at most this many points a side, no closer than the
/// gather's blocks.
constexpr int kGroundPoints = 256;
/// The ground map's blur radius per metre of height of the lattice's bottom (our choice: the
/// 8 upper directions are about 0.9 rad apart, so a cloud's copies lie about its height
/// apart; a radius of half of it merges them).
constexpr double kGroundSmoothing = 0.5;

/// The map of the ground under the world box `lo`..`hi`: its footprint widened on each side
/// by the box's top height, as far as its clouds' shade and glow reach the ground at 45°.
GroundGrid groundMapUnder(const RenderVec3& lo, const RenderVec3& hi, double spacing)
{
    const double margin = std::max(0.0, hi.z());
    GroundGrid map;
    double extent = 0.0;
    for (int a = 0; a < 2; ++a) {
        map.min[a] = lo[a] - margin;
        extent = std::max(extent, hi[a] + margin - map.min[a]);
    }
    map.spacing = std::max(spacing, extent / (kGroundPoints - 1));
    for (int a = 0; a < 2; ++a)
        map.n[a] = 2 + static_cast<int>(std::ceil((hi[a] + margin - map.min[a]) / map.spacing));
    return map;
}

/// A lattice cell's (i, j, k).
using Cell = std::array<int, 3>;

/// A voxel's share of its cell: its extinction, and the sun light it scatters for the first
/// time.
struct Share {
    std::size_t cell = 0;
    double extinction = 0.0;  ///< 0: no share (a voxel <= 0)
    double scatter = 0.0;
};

/// The transform's inverse Jacobian transpose (index-space gradient to world), as a matrix.
openvdb::Mat3d gradientToWorld(const openvdb::math::Transform& xform)
{
    openvdb::Mat3d out = openvdb::Mat3d::identity();
    for (int a = 0; a < 3; ++a) {
        openvdb::Vec3d e(0.0);
        e[a] = 1.0;
        out.setCol(a, xform.baseMap()->applyIJT(e));
    }
    return out;
}

/// The world unit outward normal of each face kind f = 2 axis + (side > 0) of the cells.
void faceNormals(const openvdb::math::Transform& xform, RenderVec3 (&out)[6])
{
    openvdb::Vec3d normal[3];
    for (int a = 0; a < 3; ++a) {
        openvdb::Vec3d e(0.0);
        e[a] = 1.0;
        normal[a] = xform.baseMap()->applyIJT(e).unitSafe();
    }
    for (int f = 0; f < 6; ++f) out[f] = normal[f / 2] * (f % 2 ? 1.0 : -1.0);
}

}  // namespace

/// The constructor's steps and the state they share: the lattice's cells of cloud (its rows),
/// their extinction and sun source, the surface faces and what each lets in, and every
/// light's fluence per row. It fills in the RenderDiffusion it is given.
class RenderDiffusion::Solver {
public:
    Solver(RenderDiffusion& out, const RenderLightMap& sunMap, const RenderMedium& medium,
           GroundPlane ground, const std::function<bool()>& cancelled);

    void sizeLattice(const openvdb::CoordBBox& active, const openvdb::Vec3d& voxel, int cellVoxels);
    void shareVoxels(const openvdb::FloatTree& tree);
    bool findCloud();
    void findFaces();
    void solveOpenView();
    void gatherAndSolve();
    void storeFields();

private:
    double beamAt(const RenderVec3& p) const;
    std::size_t cellOf(const openvdb::Coord& v) const;
    Share shareOf(const openvdb::Coord& v, float value) const;
    void addShare(const Share& share);
    void shareLeafVoxels(const openvdb::FloatTree& tree);
    void shareTileVoxels(const openvdb::FloatTree& tree);
    double diffusion(std::size_t cell) const;
    Cell cellAt(std::size_t cell) const;
    double firstMoment(std::size_t cell, int axis) const;
    RenderVec3 centreOf(const Cell& at) const;
    double litGroundSeen(const Cell& at) const;
    void seeLitGround();
    void letIn(const std::vector<GatheredView>& views);
    void assemble(SparseSystem& A, std::vector<double> (&rhs)[kLights]) const;
    openvdb::Vec3d gradientOf(const std::vector<double>& phi, std::size_t row) const;
    void limitFlux(const std::vector<double>& phi);
    void solve(int lights, double tolerance);
    GatherLattice gatherLattice() const;
    void describeClouds(GatherLattice& lattice) const;
    GatherGround groundSeen() const;
    void storeGroundLight(const GroundGrid& map, const Gathered& gathered);
    void fillEdgeCells();

    RenderDiffusion& mOut;
    const RenderLightMap& mSunMap;
    const RenderMedium& mMedium;
    const GroundPlane mGroundPlane;
    const std::function<bool()>& mCancelled;
    /// Without a sun (its light map empty) nothing scatters sun light, and the flux limiter
    /// is taken from the sky's fluence in place of the sun's.
    const bool mSunlit;
    const RenderVec3 mTravel;           ///< the sun's direction of travel
    DeltaEddington mSplit;              ///< of the phase function
    double mMeanCosine = 0.0;           ///< of the phase function, ḡ
    double mPeakless = 1.0;             ///< 1 − ω f: the sun's beam fades with it times τ
    double mEdge[3] = {0.0, 0.0, 0.0};  ///< cell edge along each axis, m
    double mPerVoxel = 0.0;             ///< a voxel's share of its cell's σ_t per unit value
    std::size_t mDense = 0;             ///< cells of the lattice
    std::vector<double> mSigmaT, mScatterOnce;  ///< per cell, dense
    std::vector<std::int32_t> mId;              ///< per cell, its row (-1: no cloud)
    std::vector<std::size_t> mCells;            ///< per row, its cell
    std::vector<double> mLimiter;               ///< per row, Wilson's R
    std::vector<std::size_t> mFirstFace;        ///< per row (and one past the last), its faces
    std::vector<GatherFace> mFaces;             ///< the surface faces, row by row
    RenderVec3 mFaceNormal[6];
    std::vector<double> mLitBelow;  ///< per row, the lit fraction of the ground it sees
    std::vector<std::array<double, kLights>> mIncoming;  ///< per face, fluence let in per light
    std::vector<double> mSolved[kLights];                ///< per light, per row
};

RenderDiffusion::Solver::Solver(RenderDiffusion& out, const RenderLightMap& sunMap,
                                const RenderMedium& medium, GroundPlane ground,
                                const std::function<bool()>& cancelled)
    : mOut(out),
      mSunMap(sunMap),
      mMedium(medium),
      mGroundPlane(ground),
      mCancelled(cancelled),
      mSunlit(!sunMap.empty()),
      mTravel(-sunMap.towardLight())
{
    // δ-Eddington: light scattered into the phase function's forward peak goes on as if
    // unscattered, so the sun's beam fades with (1 − ω f) τ and scatters for the first time
    // out of it at the rate σ_s (1 − f).
    const PhaseFunction phase = phaseOf(medium);
    mSplit = phase.deltaEddington();
    mMeanCosine = phase.meanCosine();
    mPeakless = 1.0 - medium.albedo * mSplit.peak;
}

/// Cells of c^3 voxels with one empty cell around the cloud, c grown until they fit.
/// In 64 bits: the voxels of a sparse volume may lie 2^31 apart, and the cell count of a fine
/// cell over such a span overflows 64 bits, wrapping to a count that passes.
void RenderDiffusion::Solver::sizeLattice(const openvdb::CoordBBox& active,
                                          const openvdb::Vec3d& voxel, int cellVoxels)
{
    std::int64_t dim[3];
    for (int a = 0; a < 3; ++a)
        dim[a] = std::int64_t(active.max()[a]) - std::int64_t(active.min()[a]) + 1;
    const auto cellsAlong = [&](int a, int c) { return (dim[a] + c - 1) / c + 2; };
    const auto fits = [&](int c) {
        return util::productWithin({cellsAlong(0, c), cellsAlong(1, c), cellsAlong(2, c)},
                                   kMaxCells)
            .has_value();
    };
    mOut.mVoxels = std::max(1, cellVoxels);
    while (!fits(mOut.mVoxels)) ++mOut.mVoxels;
    const int c = mOut.mVoxels;
    for (int a = 0; a < 3; ++a) mOut.mN[a] = static_cast<int>(cellsAlong(a, c));
    mOut.mFirstVoxel = active.min() - openvdb::Coord(c);
    for (int a = 0; a < 3; ++a) mEdge[a] = voxel[a] * c;
    mOut.mH = std::min({mEdge[0], mEdge[1], mEdge[2]});
    mDense = static_cast<std::size_t>(mOut.mN[0]) * static_cast<std::size_t>(mOut.mN[1]) *
             static_cast<std::size_t>(mOut.mN[2]);
    mPerVoxel = mMedium.extinction / (double(c) * c * c);
}

/// The sun's beam at p, per unit irradiance.
double RenderDiffusion::Solver::beamAt(const RenderVec3& p) const
{
    return mSunlit ? std::exp(-mPeakless * mSunMap.opticalDepth(p)) : 0.0;
}

std::size_t RenderDiffusion::Solver::cellOf(const openvdb::Coord& v) const
{
    const int c = mOut.mVoxels;
    const openvdb::Coord& first = mOut.mFirstVoxel;
    return mOut.index((v.x() - first.x()) / c, (v.y() - first.y()) / c, (v.z() - first.z()) / c);
}

Share RenderDiffusion::Solver::shareOf(const openvdb::Coord& v, float value) const
{
    Share out;
    if (!(value > 0.0f)) return out;
    out.cell = cellOf(v);
    out.extinction = mPerVoxel * value;
    const RenderVec3 world = mOut.mXform.indexToWorld(v.asVec3d());
    out.scatter = mPerVoxel * value * mMedium.albedo * (1.0 - mSplit.peak) * beamAt(world);
    return out;
}

void RenderDiffusion::Solver::addShare(const Share& share)
{
    mSigmaT[share.cell] += share.extinction;
    mScatterOnce[share.cell] += share.scatter;
}

/// Mean extinction of each cell's voxels, and the mean rate at which they scatter sun light
/// for the first time, σ_s exp(−τ_sun), taken voxel by voxel: exp(−τ) varies across a cell by
/// far more than linearly where the sun enters the cloud. The voxels of leaves, then of tiles.
void RenderDiffusion::Solver::shareVoxels(const openvdb::FloatTree& tree)
{
    mSigmaT.assign(mDense, 0.0);
    mScatterOnce.assign(mDense, 0.0);
    shareLeafVoxels(tree);
    shareTileVoxels(tree);
}

/// The sun's transmittance is the costly part of a share: leaf voxels are shared out in
/// parallel, leaves a batch at a time, and summed into the cells in leaf order, so the sums
/// do not depend on the thread count.
void RenderDiffusion::Solver::shareLeafVoxels(const openvdb::FloatTree& tree)
{
    std::vector<const openvdb::FloatTree::LeafNodeType*> leaves;
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());
    std::vector<Share> batch;
    std::vector<std::size_t> first;  // per leaf of the batch, its first share
    for (std::size_t begin = 0; begin < leaves.size();) {
        first.assign(1, 0);
        std::size_t end = begin;
        for (; end < leaves.size(); ++end) {
            const std::size_t next = first.back() + leaves[end]->onVoxelCount();
            if (end > begin && next > kVoxelBatch) break;
            first.push_back(next);
        }
        batch.assign(first.back(), Share{});
        tbb::parallel_for(begin, end, [&](std::size_t l) {
            Share* out = batch.data() + first[l - begin];
            for (auto v = leaves[l]->cbeginValueOn(); v; ++v) *out++ = shareOf(v.getCoord(), *v);
        });
        for (const Share& share : batch)
            if (share.extinction > 0.0) addShare(share);
        begin = end;
    }
}

void RenderDiffusion::Solver::shareTileVoxels(const openvdb::FloatTree& tree)
{
    auto tile = tree.cbeginValueOn();
    tile.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles only
    for (; tile; ++tile) {
        if (!(*tile > 0.0f)) continue;
        openvdb::CoordBBox box;
        tile.getBoundingBox(box);
        for (auto v = box.begin(); v; ++v) addShare(shareOf(*v, *tile));
    }
}

/// The cloud's cells, numbered in rows; false if there are none.
bool RenderDiffusion::Solver::findCloud()
{
    mId.assign(mDense, -1);
    for (std::size_t i = 0; i < mDense; ++i)
        if (mSigmaT[i] > 0.0) {
            mId[i] = static_cast<std::int32_t>(mCells.size());
            mCells.push_back(i);
        }
    if (mCells.empty()) return false;
    // The first pass takes Wilson's R as one over the cell width.
    mLimiter.assign(mCells.size(), 1.0 / mOut.mH);
    return true;
}

/// Where light streams more than it diffuses (thin cloud, steep fluence) D is limited,
/// D = 1 / (3 σ_tr + R), after Wilson's flux limiter, so that the flux D |∇φ| never exceeds
/// the fluence.
double RenderDiffusion::Solver::diffusion(std::size_t cell) const
{
    const double s = mSigmaT[cell];
    const double transport = s * (1.0 - mMedium.albedo) + s * mMedium.albedo * (1.0 - mMeanCosine);
    return 1.0 / (3.0 * transport + mLimiter[static_cast<std::size_t>(mId[cell])]);
}

Cell RenderDiffusion::Solver::cellAt(std::size_t cell) const
{
    const int* n = mOut.mN;
    return Cell{static_cast<int>(cell / (static_cast<std::size_t>(n[1]) * n[2])),
                static_cast<int>((cell / n[2]) % n[1]), static_cast<int>(cell % n[2])};
}

/// Sun light scattered once is not isotropic: its first moment, Q1 = ḡ S ω_sun per cell,
/// drives a flux 3 D Q1 that carries it on along the sun's direction, deeper into the cloud,
/// instead of letting it leak back out where it entered. Its divergence is a source,
/// −∇·(3 D Q1), taken face by face (and through Marshak's condition at the edge).
double RenderDiffusion::Solver::firstMoment(std::size_t cell, int axis) const
{
    return mSplit.g * mScatterOnce[cell] * mTravel[axis];
}

RenderVec3 RenderDiffusion::Solver::centreOf(const Cell& at) const
{
    const int c = mOut.mVoxels;
    return mOut.mXform.indexToWorld(mOut.mFirstVoxel.asVec3d() +
                                    openvdb::Vec3d(double(at[0]), double(at[1]), double(at[2])) *
                                        c +
                                    openvdb::Vec3d(0.5 * (c - 1)));
}

/// The ground a face sees is not only the point under it: it sees a disc as wide as it is
/// high, where the cloud's shadow lies offset by the sun's slant. Its lit fraction is the
/// mean sun transmittance at ground points in cosine-weighted directions below the cell
/// (4 rings of equal weight, 6 azimuths each).
double RenderDiffusion::Solver::litGroundSeen(const Cell& at) const
{
    const RenderVec3 world = centreOf(at);
    const double height = std::max(0.0, world.z());
    double sum = 0.0;
    for (int ring = 0; ring < 4; ++ring) {
        const double sin2 = (ring + 0.5) / 4.0;  // cosine-weighted: sin²θ uniform
        const double reach = height * std::sqrt(sin2 / (1.0 - sin2));
        for (int k = 0; k < 6; ++k) {
            const double phi = (k + 0.5 * (ring % 2)) * (kPi / 3.0);
            const RenderVec3 point(world.x() + reach * std::cos(phi),
                                   world.y() + reach * std::sin(phi), 0.0);
            sum += beamAt(point);
        }
    }
    return sum / 24.0;
}

/// The cloud's surface faces, row by row: where a cell of cloud meets one of clear air.
void RenderDiffusion::Solver::findFaces()
{
    const std::size_t n = mCells.size();
    mFirstFace.assign(n + 1, 0);
    for (std::size_t row = 0; row < n; ++row) {
        mFirstFace[row] = mFaces.size();
        const Cell at = cellAt(mCells[row]);
        for (int f = 0; f < 6; ++f) {
            Cell nb = at;
            nb[f / 2] += f % 2 ? 1 : -1;
            if (mId[mOut.index(nb[0], nb[1], nb[2])] < 0) mFaces.push_back({nb, f});
        }
    }
    mFirstFace[n] = mFaces.size();
    faceNormals(mOut.mXform, mFaceNormal);
    seeLitGround();
    mIncoming.resize(mFaces.size());
}

/// Per row with a face that sees below the horizon, the lit part of the ground it sees
/// (0 where the sun does not light the ground).
void RenderDiffusion::Solver::seeLitGround()
{
    const std::size_t n = mCells.size();
    mLitBelow.assign(n, 0.0);
    if (!mGroundPlane.sunlit) return;
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
        for (std::size_t f = mFirstFace[row]; f < mFirstFace[row + 1]; ++f)
            if (mFaceNormal[mFaces[f].kind].z() < 1.0) {
                mLitBelow[row] = litGroundSeen(cellAt(mCells[row]));
                break;
            }
    });
}

/// The fluence each face lets in per unit light: with no views, the open view, in the
/// proportions (1 ± n_z) / 2 of its cosine-weighted view, of sky above the horizon and of
/// ground below it (its lit part that of the ground it sees); with views, what it sees through
/// the clear air (SurfaceGather.h).
void RenderDiffusion::Solver::letIn(const std::vector<GatheredView>& views)
{
    static_assert(kGathered == GatherLattice::kUnits);
    tbb::parallel_for(std::size_t(0), mCells.size(), [&](std::size_t row) {
        for (std::size_t f = mFirstFace[row]; f < mFirstFace[row + 1]; ++f) {
            const double up = 0.5 * (1.0 + mFaceNormal[mFaces[f].kind].z());
            std::array<double, kLights>& in = mIncoming[f];
            in.fill(0.0);
            if (views.empty()) {
                in[Sky] = up;
                in[Ground] = 1.0 - up;
                in[LitGround] = (1.0 - up) * mLitBelow[row];
            } else {
                const GatheredView& v = views[f];
                for (int l = 0; l < kGathered; ++l)
                    in[l] = up * v.emitted[0][l] + (1.0 - up) * v.emitted[1][l];
                in[Sky] += up * v.transmittance[0];
                if (mGroundPlane.present) {
                    const double* g = v.ground;
                    in[Ground] += (1.0 - up) * g[GatheredView::SkyLit];
                    in[LitGround] += (1.0 - up) * g[GatheredView::SunLit];
                    in[SunGlowGround] += (1.0 - up) * g[GatheredView::Glow + Sun];
                    in[SkyGlowGround] += (1.0 - up) * g[GatheredView::Glow + Sky];
                } else {
                    in[Ground] += (1.0 - up) * v.transmittance[1];
                }
            }
            for (double& x : in) x *= 4.0 * kPi;
        }
    });
}

/// The system of every light with the current limiter and what the faces let in: the cells'
/// couplings, absorption and Marshak's boundary terms, and per light its right-hand side
/// (the sun's with its source, Q0 − ∇·(3 D Q1)).
void RenderDiffusion::Solver::assemble(SparseSystem& A, std::vector<double> (&rhs)[kLights]) const
{
    const std::size_t n = mCells.size();
    A.diag.assign(n, 0.0);
    A.neighbour.resize(6 * n);
    A.coupling.assign(6 * n, 0.0f);
    for (auto& b : rhs) b.assign(n, 0.0);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
        const std::size_t cell = mCells[row];
        const Cell at = cellAt(cell);
        const double Di = diffusion(cell);
        for (int f = 0; f < 6; ++f) A.neighbour[6 * row + f] = static_cast<std::int32_t>(row);
        double diag = mSigmaT[cell] * (1.0 - mMedium.albedo);
        double drift = 0.0;  // outflow of 3 D Q1 through the cell's faces, per volume
        std::size_t face = mFirstFace[row];
        for (int f = 0; f < 6; ++f) {
            const int axis = f / 2, step = f % 2 ? 1 : -1;
            Cell nb = at;
            nb[axis] += step;
            const std::size_t other = mOut.index(nb[0], nb[1], nb[2]);  // the halo keeps it in
            const double ha = mEdge[axis];
            if (mId[other] >= 0) {
                const double Dj = diffusion(other);
                const double k = 2.0 * Di * Dj / ((Di + Dj) * ha * ha);
                A.neighbour[6 * row + f] = mId[other];
                A.coupling[6 * row + f] = static_cast<float>(k);
                diag += k;
                const double q1 = 0.5 * (firstMoment(cell, axis) + firstMoment(other, axis));
                drift += 3.0 * (2.0 * Di * Dj / (Di + Dj)) * q1 * step / ha;
                continue;
            }
            // Marshak: the face loses k φ and lets in k Φ, Φ the fluence of what it sees.
            const double k = 2.0 * Di / (ha * (ha + 4.0 * Di));
            diag += k;
            drift += 3.0 * Di * firstMoment(cell, axis) * step / (ha + 4.0 * Di);
            for (int l = 0; l < kLights; ++l) rhs[l][row] += k * mIncoming[face][l];
            ++face;
        }
        A.diag[row] = diag;
        rhs[Sun][row] += mScatterOnce[cell] - drift;
    });
}

/// ∇φ (world, 1/m) by central differences, one-sided at the cloud's edge.
openvdb::Vec3d RenderDiffusion::Solver::gradientOf(const std::vector<double>& phi,
                                                   std::size_t row) const
{
    const Cell at = cellAt(mCells[row]);
    openvdb::Vec3d perCell(0.0);
    for (int axis = 0; axis < 3; ++axis) {
        double value[2] = {phi[row], phi[row]};
        int span = 0;
        for (int side = 0; side < 2; ++side) {
            Cell nb = at;
            nb[axis] += side ? 1 : -1;
            const std::int32_t other = mId[mOut.index(nb[0], nb[1], nb[2])];
            if (other < 0) continue;
            value[side] = phi[static_cast<std::size_t>(other)];
            ++span;
        }
        perCell[axis] = span ? (value[1] - value[0]) / span : 0.0;
    }
    return mOut.mGradientToWorld * (perCell / double(mOut.mVoxels));
}

/// Wilson's limiter from the sun's fluence, R = |∇φ| / φ, at most 4 per cell width so that
/// no cell is cut off.
void RenderDiffusion::Solver::limitFlux(const std::vector<double>& phi)
{
    tbb::parallel_for(std::size_t(0), mCells.size(), [&](std::size_t row) {
        const double most = kMostLimit / mOut.mH;
        const double grad = gradientOf(phi, row).length();
        mLimiter[row] = phi[row] > 0.0 ? std::min(grad / phi[row], most) : most;
    });
}

/// Solves the first `lights` lights with the current limiter and view (those there are),
/// each from where it stands.
void RenderDiffusion::Solver::solve(int lights, double tolerance)
{
    SparseSystem A;
    std::vector<double> rhs[kLights];
    assemble(A, rhs);
    std::vector<SolveColumn> columns;
    for (int l = 0; l < lights; ++l) {
        if (l == LitGround && !mGroundPlane.sunlit) continue;
        if ((l == SunGlowGround || l == SkyGlowGround) && !mGroundPlane.present) continue;
        columns.push_back({&rhs[l], &mSolved[l]});
    }
    mOut.mIterations =
        std::max(mOut.mIterations,
                 solveConjugateGradient(A, columns, tolerance, kMaxIterations, mCancelled));
}

/// The solves under the open view: the sun's (the sky's without a sun), the flux limiter
/// updated from each, then every gathered light's, which only feeds the first gather.
void RenderDiffusion::Solver::solveOpenView()
{
    letIn({});
    // Start from what a cell would hold alone in its surroundings: 2π per unit radiance of
    // the sky or the ground.
    const double start[kLights] = {0.0, 2.0 * kPi, 2.0 * kPi, 0.0, 0.0, 0.0};
    for (int l = 0; l < kLights; ++l) mSolved[l].assign(mCells.size(), start[l]);
    const int limiting = mSunlit ? Sun : Sky;
    for (int pass = 0; pass < kLimiterPasses; ++pass) {
        const bool last = pass + 1 == kLimiterPasses;
        solve(last ? kGathered : limiting + 1, kLimiterTolerance);
        if (!last) limitFlux(mSolved[limiting]);
    }
}

/// Then each face lets in what it sees through the clear air, the clouds' scattered light of
/// the last solve included (their source radiance J = ω φ / 4π), and every light is solved
/// again, from where it stands; twice, so that the clouds' light a face sees comes from a
/// solve in which the clouds lit and shaded one another (the open view's solve lights every
/// cloud by the whole sky).
void RenderDiffusion::Solver::gatherAndSolve()
{
    GatherLattice lattice = gatherLattice();
    const GatherGround seen = groundSeen();
    Gathered gathered;
    for (int pass = 0; pass < kGatherPasses; ++pass) {
        describeClouds(lattice);
        const bool last = pass + 1 == kGatherPasses;
        gathered = gatherSurfaceLight(lattice, mFaces, seen,
                                      last ? kGatherDirections : kFirstGatherDirections,
                                      last ? kGatherClearance : kFirstGatherClearance,
                                      last ? kGatherStride : kFirstGatherStride, mCancelled);
        letIn(gathered.faces);
        solve(kLights, last ? kTolerance : kFeedTolerance);
    }
    if (mGroundPlane.present) storeGroundLight(seen.map, gathered);
}

/// The lattice as the gather sees it, its clouds still to be described.
GatherLattice RenderDiffusion::Solver::gatherLattice() const
{
    GatherLattice lattice;
    for (int a = 0; a < 3; ++a) lattice.n[a] = mOut.mN[a];
    for (int f = 0; f < 6; ++f) lattice.normal[f] = mFaceNormal[f];
    const RenderVec3 origin = mOut.mXform.worldToIndex(RenderVec3(0.0));
    lattice.origin = centreOf({0, 0, 0});
    for (int a = 0; a < 3; ++a) {
        RenderVec3 e(0.0);
        e[a] = 1.0;
        lattice.cellsPerMetre.setCol(a,
                                     (mOut.mXform.worldToIndex(e) - origin) / double(mOut.mVoxels));
    }
    lattice.albedo = mMedium.albedo;
    lattice.split = mSplit;
    lattice.travel = mTravel;
    lattice.clouds.resize(mCells.size());
    return lattice;
}

/// Each cloud cell's extinction, sun source and, per gathered light, its fluence and net flux
/// as the last solve left them.
void RenderDiffusion::Solver::describeClouds(GatherLattice& lattice) const
{
    tbb::parallel_for(std::size_t(0), mCells.size(), [&](std::size_t row) {
        const std::size_t cell = mCells[row];
        GatherLattice::Cloud& cloud = lattice.clouds[row];
        cloud.cell = cell;
        cloud.extinction = static_cast<float>(mSigmaT[cell]);
        cloud.beam = static_cast<float>(mScatterOnce[cell] / mSigmaT[cell]);
        const double D = diffusion(cell);
        for (int l = 0; l < kGathered; ++l) {
            cloud.phi[l] = static_cast<float>(mSolved[l][row]);
            RenderVec3 flux = gradientOf(mSolved[l], row) * -D;
            if (l == Sun)
                for (int a = 0; a < 3; ++a) flux[a] += 3.0 * D * firstMoment(cell, a);
            for (int a = 0; a < 3; ++a) cloud.flux[l][a] = static_cast<float>(flux[a]);
        }
    });
}

/// The ground as the gather sees it: with a ground, the map of its points under the lattice,
/// blurred as widely as the lattice's bottom is high, and lit by the sun where it is.
GatherGround RenderDiffusion::Solver::groundSeen() const
{
    GatherGround seen;
    seen.present = mGroundPlane.present;
    if (!mGroundPlane.present) return seen;
    RenderVec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    const int* n = mOut.mN;
    for (int corner = 0; corner < 8; ++corner) {
        const RenderVec3 p = centreOf(
            {corner & 1 ? n[0] - 1 : 0, corner & 2 ? n[1] - 1 : 0, corner & 4 ? n[2] - 1 : 0});
        lo = openvdb::math::minComponent(lo, p);
        hi = openvdb::math::maxComponent(hi, p);
    }
    seen.map = groundMapUnder(lo, hi, mOut.mH * kGatherStride);
    seen.smoothing = kGroundSmoothing * std::max(0.0, lo.z());
    if (mGroundPlane.sunlit) seen.sunlit = [this](const RenderVec3& p) { return beamAt(p); };
    return seen;
}

/// The ground's map and, per point, its radiance per unit light (it sends back its sky
/// light and the clouds' glow), which light the ground the camera sees.
void RenderDiffusion::Solver::storeGroundLight(const GroundGrid& map, const Gathered& gathered)
{
    mOut.mGround = map;
    mOut.mGroundLight.assign(gathered.ground.size(), {});
    for (std::size_t p = 0; p < gathered.ground.size(); ++p) {
        const GroundView& v = gathered.ground[p];
        mOut.mGroundLight[p][Ground] = static_cast<float>(v.sky);
        mOut.mGroundLight[p][SunGlowGround] = static_cast<float>(v.emitted[Sun]);
        mOut.mGroundLight[p][SkyGlowGround] = static_cast<float>(v.emitted[Sky]);
    }
}

/// The dense fields the renderer looks up: the cloud cells' fluences, D and 3 D Q1, the
/// outside's fluence elsewhere.
void RenderDiffusion::Solver::storeFields()
{
    for (int l = 0; l < kLights; ++l) mOut.mPhi[l].assign(mDense, static_cast<float>(kOutside[l]));
    mOut.mD.assign(mDense, 0.0f);
    mOut.mDrift.assign(3 * mDense, 0.0f);
    for (std::size_t row = 0; row < mCells.size(); ++row) {
        const std::size_t cell = mCells[row];
        for (int a = 0; a < 3; ++a)
            mOut.mDrift[3 * cell + a] =
                static_cast<float>(3.0 * diffusion(cell) * firstMoment(cell, a));
        for (int l = 0; l < kLights; ++l) mOut.mPhi[l][cell] = static_cast<float>(mSolved[l][row]);
        mOut.mD[cell] = static_cast<float>(diffusion(cell));
    }
    fillEdgeCells();
}

/// An empty cell next to the cloud takes the mean of its cloud neighbours, so lookups at the
/// cloud's soft edge are not pulled toward the outside's values.
void RenderDiffusion::Solver::fillEdgeCells()
{
    const int* n = mOut.mN;
    tbb::parallel_for(0, n[0], [&](int i) {
        for (int j = 0; j < n[1]; ++j)
            for (int k = 0; k < n[2]; ++k) {
                const std::size_t cell = mOut.index(i, j, k);
                if (mId[cell] >= 0) continue;
                double sum[kLights] = {}, d = 0.0;
                int count = 0;
                for (int f = 0; f < 6; ++f) {
                    int nb[3] = {i, j, k};
                    nb[f / 2] += f % 2 ? 1 : -1;
                    if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0 || nb[0] >= n[0] || nb[1] >= n[1] ||
                        nb[2] >= n[2])
                        continue;
                    const std::int32_t row = mId[mOut.index(nb[0], nb[1], nb[2])];
                    if (row < 0) continue;
                    for (int l = 0; l < kLights; ++l)
                        sum[l] += mSolved[l][static_cast<std::size_t>(row)];
                    d += mOut.mD[mCells[static_cast<std::size_t>(row)]];
                    ++count;
                }
                if (count > 0) {
                    for (int l = 0; l < kLights; ++l)
                        mOut.mPhi[l][cell] = static_cast<float>(sum[l] / count);
                    mOut.mD[cell] = static_cast<float>(d / count);
                }
            }
    });
}

RenderDiffusion::RenderDiffusion(const openvdb::FloatGrid& grid, const RenderLightMap& sunMap,
                                 const RenderMedium& medium, int cellVoxels, GroundPlane ground,
                                 const std::function<bool()>& cancelled)
    : mXform(grid.transform())
{
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    if (active.empty() || !(medium.extinction > 0.0)) return;
    mGradientToWorld = gradientToWorld(mXform);
    Solver solver(*this, sunMap, medium, ground, cancelled);
    solver.sizeLattice(active, grid.voxelSize(), cellVoxels);
    solver.shareVoxels(grid.tree());
    if (!solver.findCloud()) return;
    solver.findFaces();
    solver.solveOpenView();
    solver.gatherAndSolve();
    solver.storeFields();
}

DiffuseLight RenderDiffusion::coloured(const RenderVec3 (&radiance)[kLights]) const
{
    RenderVec3 outside(0.0);
    for (int l = 0; l < kLights; ++l) outside += radiance[l] * kOutside[l];
    DiffuseLight light(outside);
    if (empty()) return light;
    light.mSun = radiance[Sun];
    light.mXform = mXform;
    light.mGradientToWorld = mGradientToWorld;
    light.mFirstVoxel = mFirstVoxel;
    light.mVoxels = mVoxels;
    for (int a = 0; a < 3; ++a) light.mN[a] = mN[a];
    light.mCells.resize(mD.size());
    tbb::parallel_for(std::size_t(0), mD.size(), [&](std::size_t i) {
        float* lane = light.mCells[i].lane;
        for (int c = 0; c < 3; ++c) {
            double phi = 0.0;
            for (int l = 0; l < kLights; ++l) phi += radiance[l][c] * mPhi[l][i];
            lane[c] = static_cast<float>(phi);
        }
        lane[DiffuseLight::Cell::D] = mD[i];
        for (int a = 0; a < 3; ++a) lane[DiffuseLight::Cell::DriftX + a] = mDrift[3 * i + a];
        lane[DiffuseLight::Cell::kLanes - 1] = 0.0f;
    });
    light.mGround = mGround;
    light.mGroundRadiance.assign(mGroundLight.size(), RenderVec3(0.0));
    for (std::size_t p = 0; p < mGroundLight.size(); ++p)
        for (int l = 0; l < kLights; ++l)
            light.mGroundRadiance[p] += radiance[l] * double(mGroundLight[p][l]);
    return light;
}

}  // namespace cg::algo
