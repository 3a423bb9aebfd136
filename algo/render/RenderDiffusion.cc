#include "algo/render/RenderDiffusion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/render/ConjugateGradient.h"
#include "algo/render/Phase.h"
#include "algo/render/SurfaceGather.h"
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

}  // namespace

// NOLINTNEXTLINE(readability-function-size): its steps share the solver's state; to be split.
RenderDiffusion::RenderDiffusion(const openvdb::FloatGrid& grid, const RenderLightMap& sunMap,
                                 const RenderMedium& medium, int cellVoxels, GroundPlane ground,
                                 const std::function<bool()>& cancelled)
    : mXform(grid.transform())
{
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    if (active.empty() || !(medium.extinction > 0.0)) return;
    for (int a = 0; a < 3; ++a) {
        openvdb::Vec3d e(0.0);
        e[a] = 1.0;
        mGradientToWorld.setCol(a, mXform.baseMap()->applyIJT(e));
    }

    // Cells of c^3 voxels with one empty cell around the cloud, c grown until they fit.
    // In 64 bits: the voxels of a sparse volume may lie 2^31 apart, and the cell count of
    // a fine cell over such a span overflows 64 bits, wrapping to a count that passes.
    std::int64_t dim[3];
    for (int a = 0; a < 3; ++a)
        dim[a] = std::int64_t(active.max()[a]) - std::int64_t(active.min()[a]) + 1;
    const auto cellsAlong = [&](int a, int c) { return (dim[a] + c - 1) / c + 2; };
    const auto fits = [&](int c) {
        return util::productWithin({cellsAlong(0, c), cellsAlong(1, c), cellsAlong(2, c)},
                                   kMaxCells)
            .has_value();
    };
    mVoxels = std::max(1, cellVoxels);
    while (!fits(mVoxels)) ++mVoxels;
    const int c = mVoxels;
    for (int a = 0; a < 3; ++a) mN[a] = static_cast<int>(cellsAlong(a, c));
    mFirstVoxel = active.min() - openvdb::Coord(c);
    const openvdb::Vec3d voxel = grid.voxelSize();
    const double h[3] = {voxel.x() * c, voxel.y() * c, voxel.z() * c};
    mH = std::min({h[0], h[1], h[2]});
    const std::size_t dense = static_cast<std::size_t>(mN[0]) * static_cast<std::size_t>(mN[1]) *
                              static_cast<std::size_t>(mN[2]);

    // Mean extinction of each cell's voxels, and the mean rate at which they scatter sun
    // light for the first time, σ_s exp(−τ_sun), taken voxel by voxel: exp(−τ) varies
    // across a cell by far more than linearly where the sun enters the cloud.
    std::vector<double> sigmaT(dense, 0.0), scatterOnce(dense, 0.0);
    const auto cellOf = [&](const openvdb::Coord& v) {
        return index((v.x() - mFirstVoxel.x()) / c, (v.y() - mFirstVoxel.y()) / c,
                     (v.z() - mFirstVoxel.z()) / c);
    };
    const double perVoxel = medium.extinction / (double(c) * c * c);
    // δ-Eddington: light scattered into the phase function's forward peak goes on as if
    // unscattered, so the sun's beam fades with (1 − ω f) τ and scatters for the first time
    // out of it at the rate σ_s (1 − f).
    const PhaseFunction phase = phaseOf(medium);
    const DeltaEddington split = phase.deltaEddington();
    const double peakless = 1.0 - medium.albedo * split.peak;
    // Without a sun (its light map empty) nothing scatters sun light, and the flux limiter
    // is taken from the sky's fluence in place of the sun's.
    const bool sunlit = !sunMap.empty();
    const auto beamAt = [&](const RenderVec3& p) {  // the sun's beam at p, per unit irradiance
        return sunlit ? std::exp(-peakless * sunMap.opticalDepth(p)) : 0.0;
    };
    // Each voxel's share of its cell: its extinction, and the sun light it scatters for the
    // first time (the sun's transmittance, the costly part). Leaf voxels are shared out in
    // parallel, leaves a batch at a time, and summed into the cells in leaf order; then the
    // voxels of tiles. The sums do not depend on the thread count.
    struct Share {
        std::size_t cell = 0;
        double extinction = 0.0;  ///< 0: no share (a voxel <= 0)
        double scatter = 0.0;
    };
    const auto shareOf = [&](const openvdb::Coord& v, float value) {
        Share out;
        if (!(value > 0.0f)) return out;
        out.cell = cellOf(v);
        out.extinction = perVoxel * value;
        const RenderVec3 world = mXform.indexToWorld(v.asVec3d());
        out.scatter = perVoxel * value * medium.albedo * (1.0 - split.peak) * beamAt(world);
        return out;
    };
    const auto addShare = [&](const Share& share) {
        sigmaT[share.cell] += share.extinction;
        scatterOnce[share.cell] += share.scatter;
    };
    std::vector<const openvdb::FloatTree::LeafNodeType*> leaves;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());
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
    auto tile = grid.tree().cbeginValueOn();
    tile.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles only
    for (; tile; ++tile) {
        if (!(*tile > 0.0f)) continue;
        openvdb::CoordBBox box;
        tile.getBoundingBox(box);
        for (auto v = box.begin(); v; ++v) addShare(shareOf(*v, *tile));
    }

    // The cloud's cells and their couplings.
    const double gMean = phase.meanCosine();
    std::vector<std::int32_t> id(dense, -1);
    std::vector<std::size_t> cells;
    for (std::size_t i = 0; i < dense; ++i)
        if (sigmaT[i] > 0.0) {
            id[i] = static_cast<std::int32_t>(cells.size());
            cells.push_back(i);
        }
    if (cells.empty()) return;
    // Where light streams more than it diffuses (thin cloud, steep fluence) D is limited,
    // D = 1 / (3 σ_tr + R), after Wilson's flux limiter, so that the flux D |∇φ| never
    // exceeds the fluence. The first pass takes R as one over the cell width.
    std::vector<double> limiter(cells.size(), 1.0 / mH);
    const auto diffusion = [&](std::size_t cell) {
        const double s = sigmaT[cell];
        const double transport = s * (1.0 - medium.albedo) + s * medium.albedo * (1.0 - gMean);
        return 1.0 / (3.0 * transport + limiter[static_cast<std::size_t>(id[cell])]);
    };
    using Cell = std::array<int, 3>;
    const auto cellAt = [&](std::size_t cell) {
        return Cell{static_cast<int>(cell / (static_cast<std::size_t>(mN[1]) * mN[2])),
                    static_cast<int>((cell / mN[2]) % mN[1]), static_cast<int>(cell % mN[2])};
    };
    // Sun light scattered once is not isotropic: its first moment, Q1 = ḡ S ω_sun per cell,
    // drives a flux 3 D Q1 that carries it on along the sun's direction, deeper into the
    // cloud, instead of letting it leak back out where it entered. Its divergence is a
    // source, −∇·(3 D Q1), taken face by face (and through Marshak's condition at the edge).
    const RenderVec3 travel = -sunMap.towardLight();
    const auto firstMoment = [&](std::size_t cell, int axis) {
        return split.g * scatterOnce[cell] * travel[axis];
    };
    // A boundary face with outward normal n sees the sky above the horizon and the ground
    // below it, in the proportions (1 ± n_z) / 2 of its cosine-weighted view; the lit part of
    // the ground below it is the sun's transmittance down to the ground under the face.
    openvdb::Vec3d normal[3];
    for (int a = 0; a < 3; ++a) {
        openvdb::Vec3d e(0.0);
        e[a] = 1.0;
        normal[a] = mXform.baseMap()->applyIJT(e).unitSafe();
    }
    // The ground a face sees is not only the point under it: it sees a disc as wide as it is
    // high, where the cloud's shadow lies offset by the sun's slant. Its lit fraction is
    // the mean sun transmittance at ground points in cosine-weighted directions below the
    // cell (4 rings of equal weight, 6 azimuths each).
    const auto centreOf = [&](const Cell& at) {
        return mXform.indexToWorld(mFirstVoxel.asVec3d() +
                                   openvdb::Vec3d(double(at[0]), double(at[1]), double(at[2])) * c +
                                   openvdb::Vec3d(0.5 * (c - 1)));
    };
    const auto litGroundSeen = [&](const Cell& at) {
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
    };

    // The cloud's surface faces, row by row, and the fluence each lets in per unit light:
    // first the open view, (1 ± n_z) / 2 of sky and ground; once the lights are solved, what
    // the face sees through the clear air (SurfaceGather.h).
    const std::size_t n = cells.size();
    std::vector<std::size_t> firstFace(n + 1, 0);
    std::vector<GatherFace> faces;
    for (std::size_t row = 0; row < n; ++row) {
        firstFace[row] = faces.size();
        const Cell at = cellAt(cells[row]);
        for (int f = 0; f < 6; ++f) {
            Cell nb = at;
            nb[f / 2] += f % 2 ? 1 : -1;
            if (id[index(nb[0], nb[1], nb[2])] < 0) faces.push_back({nb, f});
        }
    }
    firstFace[n] = faces.size();
    RenderVec3 faceNormal[6];
    for (int f = 0; f < 6; ++f) faceNormal[f] = normal[f / 2] * (f % 2 ? 1.0 : -1.0);
    std::vector<double> litBelow(n, 0.0);
    if (ground.sunlit)
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
            for (std::size_t f = firstFace[row]; f < firstFace[row + 1]; ++f)
                if (faceNormal[faces[f].kind].z() < 1.0) {
                    litBelow[row] = litGroundSeen(cellAt(cells[row]));
                    break;
                }
        });
    std::vector<std::array<double, kLights>> incoming(faces.size());
    const auto letIn = [&](const std::vector<GatheredView>& views) {
        static_assert(kGathered == GatherLattice::kUnits);
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
            for (std::size_t f = firstFace[row]; f < firstFace[row + 1]; ++f) {
                const double up = 0.5 * (1.0 + faceNormal[faces[f].kind].z());
                std::array<double, kLights>& in = incoming[f];
                in.fill(0.0);
                if (views.empty()) {
                    in[Sky] = up;
                    in[Ground] = 1.0 - up;
                    in[LitGround] = (1.0 - up) * litBelow[row];
                } else {
                    const GatheredView& v = views[f];
                    for (int l = 0; l < kGathered; ++l)
                        in[l] = up * v.emitted[0][l] + (1.0 - up) * v.emitted[1][l];
                    in[Sky] += up * v.transmittance[0];
                    if (ground.present) {
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
    };
    letIn({});

    const auto assemble = [&](SparseSystem& A, std::vector<double>(&rhs)[kLights]) {
        A.diag.assign(n, 0.0);
        A.neighbour.resize(6 * n);
        A.coupling.assign(6 * n, 0.0f);
        for (auto& b : rhs) b.assign(n, 0.0);
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
            const std::size_t cell = cells[row];
            const Cell at = cellAt(cell);
            const double Di = diffusion(cell);
            for (int f = 0; f < 6; ++f) A.neighbour[6 * row + f] = static_cast<std::int32_t>(row);
            double diag = sigmaT[cell] * (1.0 - medium.albedo);
            double drift = 0.0;  // outflow of 3 D Q1 through the cell's faces, per volume
            std::size_t face = firstFace[row];
            for (int f = 0; f < 6; ++f) {
                const int axis = f / 2, step = f % 2 ? 1 : -1;
                Cell nb = at;
                nb[axis] += step;
                const std::size_t other = index(nb[0], nb[1], nb[2]);  // the halo keeps it in
                const double ha = h[axis];
                if (id[other] >= 0) {
                    const double Dj = diffusion(other);
                    const double k = 2.0 * Di * Dj / ((Di + Dj) * ha * ha);
                    A.neighbour[6 * row + f] = id[other];
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
                for (int l = 0; l < kLights; ++l) rhs[l][row] += k * incoming[face][l];
                ++face;
            }
            A.diag[row] = diag;
            rhs[Sun][row] += scatterOnce[cell] - drift;
        });
    };
    // ∇φ (world, 1/m) by central differences, one-sided at the cloud's edge.
    const auto gradientOf = [&](const std::vector<double>& phi, std::size_t row) {
        const Cell at = cellAt(cells[row]);
        openvdb::Vec3d perCell(0.0);
        for (int axis = 0; axis < 3; ++axis) {
            double value[2] = {phi[row], phi[row]};
            int span = 0;
            for (int side = 0; side < 2; ++side) {
                Cell nb = at;
                nb[axis] += side ? 1 : -1;
                const std::int32_t other = id[index(nb[0], nb[1], nb[2])];
                if (other < 0) continue;
                value[side] = phi[static_cast<std::size_t>(other)];
                ++span;
            }
            perCell[axis] = span ? (value[1] - value[0]) / span : 0.0;
        }
        return mGradientToWorld * (perCell / double(c));
    };
    // Wilson's limiter from the sun's fluence, R = |∇φ| / φ, at most 4 per cell width so that
    // no cell is cut off.
    const auto limitFlux = [&](const std::vector<double>& phi) {
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
            const double most = kMostLimit / mH;
            const double grad = gradientOf(phi, row).length();
            limiter[row] = phi[row] > 0.0 ? std::min(grad / phi[row], most) : most;
        });
    };
    // Start from what a cell would hold alone in its surroundings: 2π per unit radiance of
    // the sky or the ground.
    const double start[kLights] = {0.0, 2.0 * kPi, 2.0 * kPi, 0.0, 0.0, 0.0};
    std::vector<double> solved[kLights];
    for (int l = 0; l < kLights; ++l) solved[l].assign(n, start[l]);
    // Solves the first `lights` lights with the current limiter and view (those there are).
    const auto solve = [&](int lights, double tolerance) {
        SparseSystem A;
        std::vector<double> rhs[kLights];
        assemble(A, rhs);
        std::vector<SolveColumn> columns;
        for (int l = 0; l < lights; ++l) {
            if (l == LitGround && !ground.sunlit) continue;
            if ((l == SunGlowGround || l == SkyGlowGround) && !ground.present) continue;
            columns.push_back({&rhs[l], &solved[l]});
        }
        mIterations = std::max(
            mIterations, solveConjugateGradient(A, columns, tolerance, kMaxIterations, cancelled));
    };
    const int limiting = sunlit ? Sun : Sky;
    for (int pass = 0; pass < kLimiterPasses; ++pass) {
        const bool last = pass + 1 == kLimiterPasses;
        solve(last ? kGathered : limiting + 1, kLimiterTolerance);
        if (!last) limitFlux(solved[limiting]);
    }
    // Then each face lets in what it sees through the clear air, the clouds' scattered light
    // of this solve included (their source radiance J = ω φ / 4π), and every light is solved
    // again, from where it stands; twice, so that the clouds' light a face sees comes from a
    // solve in which the clouds lit and shaded one another (the open view's solve lights
    // every cloud by the whole sky).
    GatherLattice lattice;
    for (int a = 0; a < 3; ++a) lattice.n[a] = mN[a];
    for (int f = 0; f < 6; ++f) lattice.normal[f] = faceNormal[f];
    const RenderVec3 origin = mXform.worldToIndex(RenderVec3(0.0));
    lattice.origin = centreOf({0, 0, 0});
    for (int a = 0; a < 3; ++a) {
        RenderVec3 e(0.0);
        e[a] = 1.0;
        lattice.cellsPerMetre.setCol(a, (mXform.worldToIndex(e) - origin) / double(c));
    }
    lattice.albedo = medium.albedo;
    lattice.split = split;
    lattice.travel = travel;
    lattice.clouds.resize(n);
    const auto describeClouds = [&] {
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
            const std::size_t cell = cells[row];
            GatherLattice::Cloud& cloud = lattice.clouds[row];
            cloud.cell = cell;
            cloud.extinction = static_cast<float>(sigmaT[cell]);
            cloud.beam = static_cast<float>(scatterOnce[cell] / sigmaT[cell]);
            const double D = diffusion(cell);
            for (int l = 0; l < kGathered; ++l) {
                cloud.phi[l] = static_cast<float>(solved[l][row]);
                RenderVec3 flux = gradientOf(solved[l], row) * -D;
                if (l == Sun)
                    for (int a = 0; a < 3; ++a) flux[a] += 3.0 * D * firstMoment(cell, a);
                for (int a = 0; a < 3; ++a) cloud.flux[l][a] = static_cast<float>(flux[a]);
            }
        });
    };
    GatherGround seen;
    seen.present = ground.present;
    if (ground.present) {
        RenderVec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        for (int corner = 0; corner < 8; ++corner) {
            const RenderVec3 p = centreOf({corner & 1 ? mN[0] - 1 : 0, corner & 2 ? mN[1] - 1 : 0,
                                           corner & 4 ? mN[2] - 1 : 0});
            lo = openvdb::math::minComponent(lo, p);
            hi = openvdb::math::maxComponent(hi, p);
        }
        seen.map = groundMapUnder(lo, hi, mH * kGatherStride);
        seen.smoothing = kGroundSmoothing * std::max(0.0, lo.z());
        if (ground.sunlit) seen.sunlit = beamAt;
    }
    Gathered gathered;
    for (int pass = 0; pass < kGatherPasses; ++pass) {
        describeClouds();
        const bool last = pass + 1 == kGatherPasses;
        gathered = gatherSurfaceLight(lattice, faces, seen,
                                      last ? kGatherDirections : kFirstGatherDirections,
                                      last ? kGatherClearance : kFirstGatherClearance,
                                      last ? kGatherStride : kFirstGatherStride, cancelled);
        letIn(gathered.faces);
        solve(kLights, last ? kTolerance : kFeedTolerance);
    }
    if (ground.present) {
        mGround = seen.map;
        mGroundLight.assign(gathered.ground.size(), {});
        for (std::size_t p = 0; p < gathered.ground.size(); ++p) {
            const GroundView& v = gathered.ground[p];
            mGroundLight[p][Ground] = static_cast<float>(v.sky);
            mGroundLight[p][SunGlowGround] = static_cast<float>(v.emitted[Sun]);
            mGroundLight[p][SkyGlowGround] = static_cast<float>(v.emitted[Sky]);
        }
    }

    // Dense fields; an empty cell next to the cloud takes the mean of its cloud neighbours,
    // so lookups at the cloud's soft edge are not pulled toward the outside's values.
    for (int l = 0; l < kLights; ++l) mPhi[l].assign(dense, static_cast<float>(kOutside[l]));
    mD.assign(dense, 0.0f);
    mDrift.assign(3 * dense, 0.0f);
    for (std::size_t row = 0; row < n; ++row) {
        for (int a = 0; a < 3; ++a)
            mDrift[3 * cells[row] + a] =
                static_cast<float>(3.0 * diffusion(cells[row]) * firstMoment(cells[row], a));
        for (int l = 0; l < kLights; ++l) mPhi[l][cells[row]] = static_cast<float>(solved[l][row]);
        mD[cells[row]] = static_cast<float>(diffusion(cells[row]));
    }
    tbb::parallel_for(0, mN[0], [&](int i) {
        for (int j = 0; j < mN[1]; ++j)
            for (int k = 0; k < mN[2]; ++k) {
                const std::size_t cell = index(i, j, k);
                if (id[cell] >= 0) continue;
                double sum[kLights] = {}, d = 0.0;
                int count = 0;
                for (int f = 0; f < 6; ++f) {
                    int nb[3] = {i, j, k};
                    nb[f / 2] += f % 2 ? 1 : -1;
                    if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0 || nb[0] >= mN[0] || nb[1] >= mN[1] ||
                        nb[2] >= mN[2])
                        continue;
                    const std::int32_t row = id[index(nb[0], nb[1], nb[2])];
                    if (row < 0) continue;
                    for (int l = 0; l < kLights; ++l)
                        sum[l] += solved[l][static_cast<std::size_t>(row)];
                    d += mD[cells[static_cast<std::size_t>(row)]];
                    ++count;
                }
                if (count > 0) {
                    for (int l = 0; l < kLights; ++l)
                        mPhi[l][cell] = static_cast<float>(sum[l] / count);
                    mD[cell] = static_cast<float>(d / count);
                }
            }
    });
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
