#pragma once
/// Runs the small version of a shipped graph and gathers the statistics of its outputs.

#include <filesystem>
#include <string>
#include <vector>

#include "golden/GoldenSpecs.h"
#include "golden/GoldenStats.h"

namespace cg::golden {

/// Loads graphs/<spec.name>.json through the library, shrinks it, applies `overrides`
/// ("node.param=value", as --set takes them), cooks spec.frames into a temporary output
/// directory and returns, for every frame, the statistics of every output that changed since
/// the last recorded frame ("<frame>/<node>.<port>/<stat>"), plus the files written
/// (GoldenFiles.h).
Stats runGolden(const GoldenSpec& spec, const std::vector<std::string>& overrides = {});

/// Where the shipped graphs and the expected files are (from the build).
std::filesystem::path graphsDir();
std::filesystem::path expectedDir();

}  // namespace cg::golden
