#pragma once
/// Stored golden statistics: the expected file's format (sorted keys, one statistic a line)
/// and the comparison with tolerances that names the graph, frame, node and statistic.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "golden/GoldenStats.h"

namespace cg::golden {

/// The tolerance of a kind: |actual - expected| <= max(relative * |expected|, absolute).
struct Tolerance {
    double relative = 0.0;
    double absolute = 0.0;
};
Tolerance toleranceOf(Kind kind);

/// The expected file's content: {"frames": [...], "graph": "graphs/x.json", "stats": {...}},
/// counts as JSON integers, other values rounded to 9 significant digits (a float's digits
/// and then some: the tolerances are far wider).
nlohmann::json toJson(const std::string& graphFile, const std::vector<int>& frames,
                      const Stats& stats);
/// Writes it with one statistic per line.
void writeExpected(const std::filesystem::path& file, const nlohmann::json& expected);

/// One message per statistic that differs, is missing or is new; empty when all match.
/// Statistic names are "<frame>/<node>.<port>/<statistic>", "files/<dir>/*.<ext>" or
/// "files/<dir>/<file>/<statistic>"; messages spell them out, e.g. "frame 80, node 'voxelize'
/// output 'volume': active_voxels is 1240, expected 1234 (exact)".
std::vector<std::string> compare(const Stats& actual, const nlohmann::json& expectedStats);

}  // namespace cg::golden
