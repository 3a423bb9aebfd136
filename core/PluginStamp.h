#pragma once
/// The ABI stamp a plugin carries in its file, read without loading the library: dlopen runs
/// a library's static constructors, and code built against another engine must not run.
///
/// CLOUDGRAPH_PLUGIN puts a PluginStamp in the ELF section ".cloudgraph_plugin"; the loader
/// finds that section through the section headers and reads the version from the file.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace cg {

struct PluginStamp {
    char magic[16];  ///< kPluginStampMagic
    std::int32_t abiVersion;
};

constexpr char kPluginStampMagic[16] = "CloudGraphPlugn";
constexpr const char* kPluginStampSection = ".cloudgraph_plugin";

/// Reads `size` bytes at `offset` into `out`; false when the file is shorter.
using ByteSource = std::function<bool(std::uint64_t offset, void* out, std::size_t size)>;

/// The stamp's ABI version from an ELF image of `fileSize` bytes read through `read`.
/// nullopt: a valid ELF library without a stamp (not a CloudGraph plugin). Throws
/// std::runtime_error saying what is wrong for anything that is not a well-formed 64-bit
/// little-endian ELF file of this machine's architecture.
std::optional<std::int32_t> readPluginStamp(const ByteSource& read, std::uint64_t fileSize);

/// The same for a file; throws std::runtime_error also when it is not a regular file.
std::optional<std::int32_t> readPluginStampFromFile(const std::filesystem::path& path);

}  // namespace cg
