#pragma once
/// Binary little-endian PLY point clouds ("ply / format binary_little_endian 1.0 / comment
/// CloudGraph ... / element vertex N / property <type> <name> ... / end_header", then N
/// records), as read by Blender, Houdini and ParaView. The one PLY writer: the particle and
/// cloud-particle files are lists of properties for it.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace cg::formats {

enum class PlyType { Float, Int, UInt, UChar };

/// One property of every vertex: element i is data[i * stride] (stride in elements, e.g. 3
/// for one coordinate of interleaved xyz). `data` null: every value is 0. Int properties read
/// std::int32_t, UInt std::uint32_t, UChar std::uint8_t and Float float.
struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float;
    const void* data = nullptr;
    std::size_t stride = 1;
};

/// Writes `count` vertices with `properties`, in order, to `path` (created or truncated).
/// `comment` goes after "CloudGraph " on the comment line (line breaks become spaces).
/// Throws std::runtime_error naming the file when it cannot be written. `poll`, when set, is
/// called now and then and may throw to cancel.
void writeBinaryPly(const std::filesystem::path& path, std::size_t count,
                    const std::vector<PlyProperty>& properties, const std::string& comment = "",
                    const std::function<void()>& poll = {});

/// The header writeBinaryPly writes for these arguments, through "end_header\n".
std::string binaryPlyHeader(std::size_t count, const std::vector<PlyProperty>& properties,
                            const std::string& comment);
/// Bytes of one record of `properties`.
std::size_t plyRecordBytes(const std::vector<PlyProperty>& properties);
/// Packs the records [begin, end) of `properties` at `out`, (end - begin) plyRecordBytes bytes,
/// as writeBinaryPly writes them.
void packPlyRecords(const std::vector<PlyProperty>& properties, std::size_t begin, std::size_t end,
                    unsigned char* out);

}  // namespace cg::formats
