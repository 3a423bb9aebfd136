#pragma once
/// Binary PLY (binary_little_endian 1.0) point clouds of vapour particles, as read by
/// Blender, Houdini and ParaView. The file is
///
///   ply
///   format binary_little_endian 1.0
///   comment CloudGraph <comment>
///   element vertex N
///   property float x            (m)
///   property float y            (m)
///   property float z            (m, height P_vz)
///   property float vx           (m/s, the wind and outflow that moved it; 0 in calm air)
///   property float vy           (m/s)
///   property float vz           (m/s, U_vz)
///   property float temperature  (degrees Celsius, T_v)
///   property int id
///   property int state          (0 vapour, 1 condensed)
///   property int home_cell
///   end_header
///
/// followed by N records of 40 bytes, every value little-endian whatever the host order,
/// written by writeBinaryPly (PlyFile.h).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace cg::formats {

/// Borrowed arrays of `count` particles each. `state`, `vx` and `vy` may be null (zeros).
struct PlyParticleView {
    std::size_t count = 0;
    const float* x = nullptr;            ///< metres
    const float* y = nullptr;            ///< metres
    const float* z = nullptr;            ///< metres
    const float* vx = nullptr;           ///< m/s, optional
    const float* vy = nullptr;           ///< m/s, optional
    const float* vz = nullptr;           ///< m/s
    const float* temperature = nullptr;  ///< degrees Celsius
    const std::uint32_t* id = nullptr;
    const std::int32_t* state = nullptr;  ///< optional
    const std::uint32_t* homeCell = nullptr;
};

/// Bytes of one binary record (seven floats, three ints).
constexpr std::size_t kPlyRecordBytes = 10 * 4;

/// Writes `particles` to `path` (created or truncated). `comment` goes after "CloudGraph "
/// on the comment line (line breaks become spaces). Throws std::invalid_argument when a
/// required array is null, std::range_error when an id or home cell does not fit a PLY int,
/// and std::runtime_error naming the file when it cannot be written. `poll`, when set, is
/// called now and then and may throw to cancel.
void writeParticlesPly(const std::filesystem::path& path, const PlyParticleView& particles,
                       const std::string& comment = "", const std::function<void()>& poll = {});

}  // namespace cg::formats
