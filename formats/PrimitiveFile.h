#pragma once
/// The primitive-set file (.cgp): every frame of a 3D cloud primitive set, with random access
/// to any frame. All numbers little-endian.
///
///   offset  size  field
///   0       8     magic "CGPRIM\r\n" (the CR LF catches text-mode mangling)
///   8       4     u32 version = 1
///   12      4     u32 F, frame count (>= 1)
///   16      8     f64 Delta s, seconds of physical time per frame (> 0)
///   24      4     u32 units of the positions: 1 = metres, relative to the cloud origin
///   28      4     u32 reserved, 0
///   32      24    f32 bounds: min x, y, z then max x, y, z over all frames (0 if empty)
///   56      8     u64 XXH3-64 of bytes 0..55 and of the frame index that follows
///   64      16 F  frame index, per frame s: u64 offset of its block, u32 N_f(s), u32 0
///   ...           frame blocks, in order, back to back; block s is
///                   u32 s, u32 N_f(s), N_f(s) x 3 f32 positions (x y z, m),
///                   u64 XXH3-64 of the block's bytes before it
///
/// The blocks tile the file exactly: block 0 starts at 64 + 16 F, each next block right after
/// the previous one, and the last one ends at the end of the file; N_f never decreases.
/// Readers check all of it, and every size against the file size before allocating.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace cg::formats {

constexpr std::uint32_t kPrimitiveFileVersion = 1;
constexpr std::uint32_t kPrimitiveUnitsMetres = 1;
constexpr std::size_t kPrimitiveHeaderBytes = 64;
constexpr std::size_t kPrimitiveIndexEntryBytes = 16;
/// The largest primitive file any reader opens (`info`, PrimitiveLoad, the content hash):
/// util::nodeAllocationLimitBytes(), the machine-relative limit of one node's value, because
/// reading a frame allocates up to the file's size. Larger files are refused before anything
/// is allocated; a primitive set of the paper's size is ~100 MB.
std::uint64_t maxPrimitiveFileBytes();

/// Writes a primitive set atomically (temporary file beside `path`, then rename). `counts` and
/// `positions` as in PrimitiveSetData. Throws std::invalid_argument on inconsistent sizes and
/// std::runtime_error naming the file when it cannot be written.
void writePrimitiveFile(const std::filesystem::path& path, double frameTime,
                        const std::vector<std::uint32_t>& counts,
                        const std::vector<float>& positions);

/// An open, validated primitive-set file; frames are read on demand. Every error is a
/// formats::FormatError whose place is "<file>:<byte offset>".
class PrimitiveFileReader {
public:
    /// Opens `path` and validates the header and the frame index against the file size; a file
    /// over maxPrimitiveFileBytes() is refused before anything is read.
    explicit PrimitiveFileReader(const std::filesystem::path& path);

    int frames() const { return static_cast<int>(mCounts.size()); }
    double frameTime() const { return mFrameTime; }
    std::uint32_t units() const { return mUnits; }
    const float* boundsMin() const { return mBounds; }
    const float* boundsMax() const { return mBounds + 3; }
    const std::vector<std::uint32_t>& counts() const { return mCounts; }
    std::uint64_t fileSize() const { return mFileSize; }
    std::uint64_t frameOffset(int s) const { return mOffsets.at(static_cast<std::size_t>(s)); }

    /// Reads frame s alone (3 N_f(s) floats), checking its block and checksum.
    std::vector<float> readFrame(int s);
    /// Reads every frame, concatenated (the layout of PrimitiveSetData::positions).
    std::vector<float> readAll();

private:
    [[noreturn]] void fail(std::uint64_t offset, const std::string& message) const;
    void readAt(std::uint64_t offset, void* out, std::size_t size);

    std::filesystem::path mPath;
    std::ifstream mIn;
    std::uint64_t mFileSize = 0;
    double mFrameTime = 0.0;
    std::uint32_t mUnits = 0;
    float mBounds[6] = {0, 0, 0, 0, 0, 0};
    std::vector<std::uint32_t> mCounts;
    std::vector<std::uint64_t> mOffsets;
};

/// XXH3-64 of the whole file's bytes (the content hash that keys PrimitiveLoad). Throws
/// formats::FormatError naming the file when it cannot be read.
std::uint64_t primitiveFileContentHash(const std::filesystem::path& path);

}  // namespace cg::formats
