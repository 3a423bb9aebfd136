#include "formats/VdbFileWriter.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <xxhash.h>

#include "util/AtomicFile.h"

namespace cg::formats {

namespace {

constexpr std::int64_t kVdbMagic = 0x56444220;
constexpr std::uint32_t kNodeMaskCompression = 222;  // from this version, no compression byte
constexpr std::size_t kUuidChars = 36;

std::uint32_t u32At(const std::vector<char>& bytes, std::size_t at)
{
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}

/// Rewrites, in place, the UUID of the VDB file at `path` (just written by openvdb::io::File).
void setContentUuid(const std::filesystem::path& path)
{
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    if (!file) throw std::runtime_error("cannot open " + path.string() + " to set its UUID");
    const std::vector<char> bytes((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
    // magic (8), file version (4), library version (2 x 4), grid offsets flag (1),
    // before version 222 a compression flag (1), then the UUID as 36 characters.
    std::int64_t magic = 0;
    if (bytes.size() >= 8) std::memcpy(&magic, bytes.data(), sizeof magic);
    const std::size_t uuidAt =
        bytes.size() >= 12 && u32At(bytes, 8) < kNodeMaskCompression ? 22 : 21;
    if (magic != kVdbMagic || bytes.size() < uuidAt + kUuidChars)
        throw std::runtime_error(path.string() + " is not a VDB file: cannot set its UUID");

    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    XXH3_128bits_update(state, bytes.data(), uuidAt);
    XXH3_128bits_update(state, bytes.data() + uuidAt + kUuidChars,
                        bytes.size() - uuidAt - kUuidChars);
    const XXH128_hash_t h = XXH3_128bits_digest(state);
    XXH3_freeState(state);
    // Laid out as a version 4 (random) UUID, which is what the hash stands in for.
    const std::uint64_t hi = (h.high64 & ~std::uint64_t{0xF000}) | 0x4000;
    const std::uint64_t lo = (h.low64 & ~(std::uint64_t{0xC} << 60)) | (std::uint64_t{0x8} << 60);
    char uuid[kUuidChars + 1];
    std::snprintf(uuid, sizeof uuid, "%08x-%04x-%04x-%04x-%012llx", static_cast<unsigned>(hi >> 32),
                  static_cast<unsigned>((hi >> 16) & 0xFFFF), static_cast<unsigned>(hi & 0xFFFF),
                  static_cast<unsigned>(lo >> 48),
                  static_cast<unsigned long long>(lo & 0xFFFFFFFFFFFFull));
    file.clear();
    file.seekp(static_cast<std::streamoff>(uuidAt));
    file.write(uuid, kUuidChars);
    file.flush();
    if (!file) throw std::runtime_error("cannot write the UUID of " + path.string());
}

}  // namespace

void writeVdbFile(const std::filesystem::path& target, const openvdb::GridBase::ConstPtr& grid,
                  const std::string& creator, std::optional<std::uint32_t> compression,
                  const std::function<void()>& beforeCommit)
{
    writeVdbFile(target, openvdb::GridCPtrVec{grid}, creator, compression, beforeCommit);
}

void writeVdbFile(const std::filesystem::path& target, const openvdb::GridCPtrVec& grids,
                  const std::string& creator, std::optional<std::uint32_t> compression,
                  const std::function<void()>& beforeCommit)
{
    // OpenVDB truncates and writes in place: write beside, then rename.
    util::AtomicOutput out(target);
    {
        openvdb::io::File file(out.tempPath().string());
        if (compression) file.setCompression(*compression);
        openvdb::MetaMap fileMeta;
        fileMeta.insertMeta("creator", openvdb::StringMetadata(creator));
        file.write(grids, fileMeta);
        file.close();
    }
    setContentUuid(out.tempPath());
    if (beforeCommit) beforeCommit();
    out.commit();
}

}  // namespace cg::formats
