#pragma once
/// A synthetic cauliflower cumulus as a fog volume, for rendering tests and stills that must
/// not wait for the particle pipeline: a hierarchy of overlapping spheres (big base blobs
/// whose bottoms are cut flat at the cloud base, smaller blobs piled on top), each with a soft
/// edge, summed, eroded at the edges by billow noise, rasterised into a sparse FloatGrid.
/// Deterministic: a pure function of the settings, whatever the thread count.

#include <cstdint>
#include <vector>

#include <openvdb/openvdb.h>

namespace cg::algo {

struct SyntheticCumulusSettings {
    std::uint64_t seed = 1;
    double voxelSize = 20.0;       ///< m
    double baseHeight = 800.0;     ///< m; the flat cloud base (z)
    double baseRadius = 700.0;     ///< m; half-width of the footprint of the base blobs
    double towerHeight = 1.0;      ///< vertical stretch of the pile (1 = as wide as tall)
    int levels = 4;                ///< levels of the blob hierarchy, >= 1
    int children = 4;              ///< blobs placed on each blob of the level below
    double edgeSoftness = 0.35;    ///< fraction of a blob's radius over which it fades out
    double noiseAmplitude = 0.55;  ///< edge erosion by noise, 0 = smooth spheres
    double noiseScale = 180.0;     ///< m; wavelength of the largest noise octave
    double density = 1.0;          ///< interior density, in (0, 1]
};

struct CumulusBlob {
    double x, y, z;  ///< centre, m
    double radius;   ///< m
};

/// The blob hierarchy: 7 base blobs, then `children` blobs on the upper side of each blob of
/// the previous level, each 0.55 to 0.7 times its parent's radius (SyntheticCumulusBlobs.cc).
std::vector<CumulusBlob> cumulusBlobs(const SyntheticCumulusSettings& settings);

/// Upper bound on the voxels of the bounding box of the cloud, for allocation checks.
std::uint64_t cumulusVoxelBound(const SyntheticCumulusSettings& settings);

/// Rasterises the blobs into a fog volume "density" (values in [0, 1], 0 below the base, the
/// transform's voxel size voxelSize metres, voxel centres at index × voxelSize). Leaves are
/// filled in parallel and inserted in a fixed order.
openvdb::FloatGrid::Ptr rasterizeCumulus(const std::vector<CumulusBlob>& blobs,
                                         const SyntheticCumulusSettings& settings);

}  // namespace cg::algo
