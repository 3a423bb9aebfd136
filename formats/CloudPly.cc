#include "formats/CloudPly.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "formats/PlyFile.h"
#include "util/AtomicFile.h"

namespace cg::formats {

namespace {

/// The records' properties; with motion, vx, vy, vz and id after the paper's ones.
std::vector<PlyProperty> cloudProperties(std::size_t count, const float* positions,
                                         const std::uint8_t* levels, const std::uint32_t* sources,
                                         bool motion = false, const float* velocities = nullptr,
                                         const std::uint32_t* ids = nullptr)
{
    // No positions (the header alone needs none): every coordinate property is null.
    const bool any = count > 0 && positions != nullptr;
    std::vector<PlyProperty> out = {{"x", PlyType::Float, any ? positions : nullptr, 3},
                                    {"y", PlyType::Float, any ? positions + 1 : nullptr, 3},
                                    {"z", PlyType::Float, any ? positions + 2 : nullptr, 3},
                                    {"level", PlyType::UChar, levels},
                                    {"source", PlyType::UInt, sources}};
    if (!motion) return out;
    const bool moving = count > 0 && velocities != nullptr;
    out.push_back({"vx", PlyType::Float, moving ? velocities : nullptr, 3});
    out.push_back({"vy", PlyType::Float, moving ? velocities + 1 : nullptr, 3});
    out.push_back({"vz", PlyType::Float, moving ? velocities + 2 : nullptr, 3});
    out.push_back({"id", PlyType::UInt, ids});
    return out;
}

[[noreturn]] void failed(const std::filesystem::path& path, int error)
{
    throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(error));
}

}  // namespace

void writeCloudPly(const std::filesystem::path& path, std::size_t count, const float* positions,
                   const std::uint8_t* levels, const std::uint32_t* sources,
                   const std::string& comment, const std::function<void()>& poll)
{
    writeBinaryPly(path, count, cloudProperties(count, positions, levels, sources), comment, poll);
}

CloudPlyChunkWriter::CloudPlyChunkWriter(
    std::filesystem::path path, std::vector<std::pair<std::uint64_t, std::uint64_t>> chunks,
    const std::string& comment, bool motion)
    : mPath(std::move(path)), mMotion(motion)
{
    std::sort(chunks.begin(), chunks.end());
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        if (i > 0 && chunks[i].first == chunks[i - 1].first)
            throw std::invalid_argument("cloud PLY: chunk " + std::to_string(chunks[i].first) +
                                        " given twice");
        mTotal += chunks[i].second;
    }
    const auto properties = cloudProperties(mTotal, nullptr, nullptr, nullptr, mMotion);
    const std::string header = binaryPlyHeader(mTotal, properties, comment);
    const std::size_t recordBytes = plyRecordBytes(properties);
    std::uint64_t offset = header.size();
    for (const auto& [first, count] : chunks) {
        mFirsts.push_back(first);
        mCounts.push_back(count);
        mOffsets.push_back(offset);
        offset += count * recordBytes;
    }
    mFd = ::open(mPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (mFd < 0) failed(mPath, errno);
    if (const int error = util::writeAllAt(mFd, header.data(), header.size(), 0))
        failed(mPath, error);
}

CloudPlyChunkWriter::~CloudPlyChunkWriter()
{
    if (mFd >= 0) ::close(mFd);
}

void CloudPlyChunkWriter::write(std::uint64_t first, std::uint64_t count, const float* positions,
                                const std::uint8_t* levels, const std::uint32_t* sources,
                                const float* velocities, const std::uint32_t* ids)
{
    const auto at = std::lower_bound(mFirsts.begin(), mFirsts.end(), first);
    const std::size_t index = static_cast<std::size_t>(at - mFirsts.begin());
    if (at == mFirsts.end() || *at != first || mCounts[index] != count)
        throw std::invalid_argument("cloud PLY: chunk " + std::to_string(first) + " of " +
                                    std::to_string(count) + " particles was not announced");
    if (count == 0) return;
    const auto properties =
        cloudProperties(count, positions, levels, sources, mMotion, velocities, ids);
    thread_local std::vector<unsigned char> records;
    records.resize(count * plyRecordBytes(properties));
    packPlyRecords(properties, 0, count, records.data());
    if (const int error = util::writeAllAt(mFd, records.data(), records.size(), mOffsets[index]))
        failed(mPath, error);
}

void CloudPlyChunkWriter::close()
{
    const int fd = mFd;
    mFd = -1;
    if (fd >= 0 && ::close(fd) != 0) failed(mPath, errno);
}

}  // namespace cg::formats
