#pragma once
/// Statistics of node outputs for the golden-graph tests: a few numbers per value that change
/// when behaviour changes (counts, bounds, sums, means, coarse histograms), never file bytes.

#include <map>
#include <string>

#include <openvdb/openvdb.h>

#include "core/Data.h"

namespace cg::golden {

/// How a statistic is compared; the tolerances are in GoldenCompare.cc.
enum class Kind {
    Count,  ///< an integer: exact
    Sum,    ///< a sum over many values (voxel densities): relative tolerance
    Mean,   ///< a mean, ratio or parameter-like value: relative tolerance, absolute floor
    Bound,  ///< a coordinate in metres (bounds of particles): absolute + relative tolerance
};

struct Stat {
    Kind kind = Kind::Count;
    double value = 0.0;  ///< a Count holds an exact integer (below 2^53)
};

/// Statistic name -> value, sorted by name.
using Stats = std::map<std::string, Stat>;

/// The statistics of one output value, named without prefix ("count", "level_1_count",
/// "bounds_min_x", ...). Throws std::runtime_error for a port type it has no statistics for,
/// so a new type cannot slip through unobserved.
Stats statsOf(const Data& value);

/// A fog volume's: active voxels, leaves, voxel size, value sum and maximum, a 10-bin
/// density histogram over [0, 1] and the active index bounds.
Stats gridStats(const openvdb::FloatGrid& grid);

}  // namespace cg::golden
