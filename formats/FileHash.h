#pragma once
/// The content hash that keys a node's input file: its bytes, not its path, so a copied or
/// moved file is still a cache hit.

#include <cstdint>
#include <filesystem>
#include <string>

namespace cg::formats {

/// XXH3-64 of every byte of `path`, streamed (the file is never held whole). Throws
/// formats::FormatError naming the file when it is not a readable regular file of at most
/// `maxBytes` bytes; `what` names the kind of file in that message ("primitive file").
std::uint64_t fileContentHash(const std::filesystem::path& path, std::uint64_t maxBytes,
                              const std::string& what);

}  // namespace cg::formats
