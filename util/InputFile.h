#pragma once
/// Checks an input file before anything reads it: a device, a FIFO or a directory named
/// where a file should be must be refused, not read until memory runs out or forever.

#include <cstdint>
#include <filesystem>
#include <string>

namespace cg::util {

/// Why `path` cannot be read as an input file of at most `maxBytes` bytes, or empty when it
/// can: it must exist and be a regular file (links followed) that this process may open.
/// Opening never blocks, so a FIFO is reported, not waited on.
std::string inputFileProblem(const std::filesystem::path& path, std::uint64_t maxBytes);

}  // namespace cg::util
