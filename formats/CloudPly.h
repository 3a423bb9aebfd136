#pragma once
/// Cloud particles as a binary little-endian PLY point cloud:
///
///   ply / format binary_little_endian 1.0 / comment CloudGraph ... / element vertex N /
///   property float x / property float y / property float z / property uchar level /
///   property uint source / end_header
///
/// then N records of 17 bytes (positions in metres), little-endian on any host. With motion
/// (a chunk writer's), each record goes on with `property float vx / vy / vz` (m/s) and
/// `property uint id` (the same particle has the same id on every frame): 33 bytes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace cg::formats {

/// Throws std::runtime_error naming the file when it cannot be written.
void writeCloudPly(const std::filesystem::path& path, std::size_t count, const float* positions,
                   const std::uint8_t* levels, const std::uint32_t* sources,
                   const std::string& comment = "", const std::function<void()>& poll = {});

/// The same file written from chunks that arrive from several threads in no fixed order (a
/// frame streamed from the mapper, without a frame-sized array): told every chunk's first
/// index and particle count up front, it writes the header; each write() then packs its
/// chunk's records and writes them at their place. The file equals writeCloudPly's of the
/// particles in the order of the chunks' first indices.
class CloudPlyChunkWriter {
public:
    /// `chunks`: (first, count) of every chunk, each first once; `motion`: the records carry
    /// velocity and id. Throws std::runtime_error naming the file when it cannot be created,
    /// std::invalid_argument for a first given twice.
    CloudPlyChunkWriter(std::filesystem::path path,
                        std::vector<std::pair<std::uint64_t, std::uint64_t>> chunks,
                        const std::string& comment, bool motion = false);
    ~CloudPlyChunkWriter();
    CloudPlyChunkWriter(const CloudPlyChunkWriter&) = delete;
    CloudPlyChunkWriter& operator=(const CloudPlyChunkWriter&) = delete;

    /// Safe to call from several threads at once. `levels`, `sources`, `velocities` (3 floats a
    /// particle) or `ids` null: zeros. Throws
    /// std::invalid_argument for a chunk that was not announced with this count,
    /// std::runtime_error naming the file when the write fails.
    void write(std::uint64_t first, std::uint64_t count, const float* positions,
               const std::uint8_t* levels, const std::uint32_t* sources,
               const float* velocities = nullptr, const std::uint32_t* ids = nullptr);
    /// Closes the file. Throws std::runtime_error naming it when that fails.
    void close();

    /// Particles in the file.
    std::uint64_t count() const { return mTotal; }

private:
    std::filesystem::path mPath;
    int mFd = -1;
    std::vector<std::uint64_t> mFirsts;   ///< sorted
    std::vector<std::uint64_t> mCounts;   ///< per first
    std::vector<std::uint64_t> mOffsets;  ///< byte offset of each chunk's first record
    std::uint64_t mTotal = 0;
    bool mMotion = false;
};

}  // namespace cg::formats
