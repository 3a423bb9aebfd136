#pragma once
/// How a farm job knows its cache is the one the farm was set up with: `cloudgraph farm`
/// leaves a token record in the cache on the submitting machine, and each job, given the
/// token with --farm-token, refuses to start when it cannot read it back (the directory
/// it sees is not shared with the submitting machine).

#include <string>

#include "core/DiskCache.h"

namespace cg::cli {

/// Stores a fresh random token in the cache and returns it (16 hex digits).
std::string leaveFarmToken(const DiskCache& cache);

/// Throws InputError naming --farm-token (malformed) or --cache (token absent).
void checkFarmToken(const DiskCache& cache, const std::string& token);

}  // namespace cg::cli
