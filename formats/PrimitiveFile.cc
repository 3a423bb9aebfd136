#include "formats/PrimitiveFile.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <xxhash.h>

#include "formats/FileHash.h"
#include "formats/FormatError.h"
#include "util/AtomicFile.h"
#include "util/InputFile.h"
#include "util/LittleEndian.h"
#include "util/SystemMemory.h"

namespace cg::formats {

namespace {

constexpr char kMagic[8] = {'C', 'G', 'P', 'R', 'I', 'M', '\r', '\n'};

using util::appendF32;
using util::appendF64;
using util::appendU32;
using util::appendU64;
using util::getF32;
using util::getF64;
using util::getU32;
using util::getU64;

/// The checksum of the header and of each frame block: XXH3-64.
std::uint64_t checksum64(const void* data, std::size_t size) { return XXH3_64bits(data, size); }

}  // namespace

std::uint64_t maxPrimitiveFileBytes() { return util::nodeAllocationLimitBytes(); }

void writePrimitiveFile(const std::filesystem::path& path, double frameTime,
                        const std::vector<std::uint32_t>& counts,
                        const std::vector<float>& positions)
{
    if (counts.empty()) throw std::invalid_argument("primitive file: no frames");
    if (!(frameTime > 0.0) || !std::isfinite(frameTime))
        throw std::invalid_argument("primitive file: frame time must be positive");
    std::uint64_t total = 0;
    for (std::size_t s = 0; s < counts.size(); ++s) {
        if (s > 0 && counts[s] < counts[s - 1])
            throw std::invalid_argument("primitive file: N_f(s) decreases at frame " +
                                        std::to_string(s));
        total += counts[s];
    }
    if (positions.size() != 3 * total)
        throw std::invalid_argument("primitive file: positions do not match the counts");
    if (counts.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("primitive file: too many frames");

    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (std::size_t k = 0; k < total; ++k)
        for (int a = 0; a < 3; ++a) {
            const float v = positions[3 * k + static_cast<std::size_t>(a)];
            if (!std::isfinite(v))
                throw std::invalid_argument("primitive file: a position is not finite");
            lo[a] = k == 0 ? v : std::min(lo[a], v);
            hi[a] = k == 0 ? v : std::max(hi[a], v);
        }

    std::string head;
    head.append(kMagic, 8);
    appendU32(head, kPrimitiveFileVersion);
    appendU32(head, static_cast<std::uint32_t>(counts.size()));
    appendF64(head, frameTime);
    appendU32(head, kPrimitiveUnitsMetres);
    appendU32(head, 0);
    for (float v : lo) appendF32(head, v);
    for (float v : hi) appendF32(head, v);
    std::string index;
    std::uint64_t offset = kPrimitiveHeaderBytes + kPrimitiveIndexEntryBytes * counts.size();
    for (std::uint32_t n : counts) {
        appendU64(index, offset);
        appendU32(index, n);
        appendU32(index, 0);
        offset += 8 + 12 * std::uint64_t{n} + 8;
    }
    std::string checked = head + index;
    appendU64(head, checksum64(checked.data(), checked.size()));

    util::AtomicOutput out(path);
    {
        std::ofstream f(out.tempPath(), std::ios::binary | std::ios::trunc);
        f.write(head.data(), static_cast<std::streamsize>(head.size()));
        f.write(index.data(), static_cast<std::streamsize>(index.size()));
        std::string block;
        std::size_t first = 0;
        for (std::size_t s = 0; s < counts.size() && f; ++s) {
            block.clear();
            appendU32(block, static_cast<std::uint32_t>(s));
            appendU32(block, counts[s]);
            for (std::size_t k = 0; k < 3 * std::size_t{counts[s]}; ++k)
                appendF32(block, positions[3 * first + k]);
            appendU64(block, checksum64(block.data(), block.size()));
            f.write(block.data(), static_cast<std::streamsize>(block.size()));
            first += counts[s];
        }
        f.close();
        if (!f) throw std::runtime_error("cannot write '" + path.string() + "'");
    }
    out.commit();
}

PrimitiveFileReader::PrimitiveFileReader(const std::filesystem::path& path) : mPath(path)
{
    if (const std::string problem = util::inputFileProblem(path, maxPrimitiveFileBytes());
        !problem.empty())
        throw FormatError(path.string(), "cannot read the primitive file: it " + problem);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw FormatError(path.string(), "cannot read the primitive file: " + ec.message());
    mFileSize = size;
    mIn.open(path, std::ios::binary);
    if (!mIn) throw FormatError(path.string(), "cannot open the primitive file");
    if (mFileSize < kPrimitiveHeaderBytes)
        fail(mFileSize, "truncated: shorter than the 64-byte header");

    unsigned char h[kPrimitiveHeaderBytes];
    readAt(0, h, sizeof h);
    if (std::memcmp(h, kMagic, 8) != 0) fail(0, "not a CloudGraph primitive file (bad magic)");
    const std::uint32_t version = getU32(h + 8);
    if (version != kPrimitiveFileVersion)
        fail(8, "unsupported version " + std::to_string(version) + " (this build reads " +
                    std::to_string(kPrimitiveFileVersion) + ")");
    const std::uint32_t frames = getU32(h + 12);
    if (frames == 0) fail(12, "no frames");
    // The index must fit in the file before anything is allocated for it.
    const std::uint64_t indexEnd =
        kPrimitiveHeaderBytes + kPrimitiveIndexEntryBytes * std::uint64_t{frames};
    if (indexEnd > mFileSize)
        fail(12, "truncated: " + std::to_string(frames) + " frames need an index up to byte " +
                     std::to_string(indexEnd) + ", the file has " + std::to_string(mFileSize));
    mFrameTime = getF64(h + 16);
    if (!(mFrameTime > 0.0) || !std::isfinite(mFrameTime))
        fail(16, "the frame time is not positive");
    mUnits = getU32(h + 24);
    if (mUnits != kPrimitiveUnitsMetres) fail(24, "unknown units code " + std::to_string(mUnits));
    for (int k = 0; k < 6; ++k) {
        mBounds[k] = getF32(h + 32 + 4 * k);
        if (!std::isfinite(mBounds[k]))
            fail(32 + 4 * static_cast<std::uint64_t>(k), "bounds not finite");
    }

    std::vector<unsigned char> index(indexEnd - kPrimitiveHeaderBytes);
    readAt(kPrimitiveHeaderBytes, index.data(), index.size());
    std::vector<unsigned char> checked(h, h + 56);
    checked.insert(checked.end(), index.begin(), index.end());
    if (checksum64(checked.data(), checked.size()) != getU64(h + 56))
        fail(56, "header checksum mismatch: the header or frame index is damaged");

    mCounts.resize(frames);
    mOffsets.resize(frames);
    std::uint64_t expected = indexEnd;
    for (std::uint32_t s = 0; s < frames; ++s) {
        const unsigned char* e = index.data() + kPrimitiveIndexEntryBytes * s;
        const std::uint64_t at =
            kPrimitiveHeaderBytes + kPrimitiveIndexEntryBytes * std::uint64_t{s};
        mOffsets[s] = getU64(e);
        mCounts[s] = getU32(e + 8);
        if (mOffsets[s] != expected)
            fail(at, "frame " + std::to_string(s) + " block offset " + std::to_string(mOffsets[s]) +
                         " should be " + std::to_string(expected));
        if (s > 0 && mCounts[s] < mCounts[s - 1])
            fail(at + 8, "N_f decreases at frame " + std::to_string(s));
        expected += 16 + 12 * std::uint64_t{mCounts[s]};
        if (expected > mFileSize)
            fail(mFileSize, "truncated: frame " + std::to_string(s) + " ends at byte " +
                                std::to_string(expected) + ", the file has " +
                                std::to_string(mFileSize));
    }
    if (expected != mFileSize)
        fail(expected,
             std::to_string(mFileSize - expected) + " unexpected bytes after the last frame");
}

void PrimitiveFileReader::fail(std::uint64_t offset, const std::string& message) const
{
    throw FormatError(mPath.string() + ":" + std::to_string(offset), message);
}

void PrimitiveFileReader::readAt(std::uint64_t offset, void* out, std::size_t size)
{
    mIn.clear();
    mIn.seekg(static_cast<std::streamoff>(offset));
    mIn.read(static_cast<char*>(out), static_cast<std::streamsize>(size));
    if (!mIn) fail(offset, "read failed (" + std::to_string(size) + " bytes)");
}

std::vector<float> PrimitiveFileReader::readFrame(int s)
{
    if (s < 0 || s >= frames())
        throw std::out_of_range("primitive file: no frame " + std::to_string(s));
    const std::size_t n = mCounts[static_cast<std::size_t>(s)];
    const std::uint64_t at = mOffsets[static_cast<std::size_t>(s)];
    std::vector<unsigned char> block(16 + 12 * n);  // sizes already checked against the file
    readAt(at, block.data(), block.size());
    if (getU32(block.data()) != static_cast<std::uint32_t>(s))
        fail(at, "frame block number mismatch");
    if (getU32(block.data() + 4) != n) fail(at + 4, "frame block count disagrees with the index");
    const std::size_t body = 8 + 12 * n;
    if (checksum64(block.data(), body) != getU64(block.data() + body))
        fail(at + body, "frame " + std::to_string(s) + " checksum mismatch: the data is damaged");
    std::vector<float> xyz(3 * n);
    for (std::size_t k = 0; k < 3 * n; ++k) {
        xyz[k] = getF32(block.data() + 8 + 4 * k);
        if (!std::isfinite(xyz[k])) fail(at + 8 + 4 * k, "a position is not finite");
    }
    return xyz;
}

std::vector<float> PrimitiveFileReader::readAll()
{
    std::vector<float> all;
    std::uint64_t total = 0;
    for (std::uint32_t n : mCounts) total += n;
    all.reserve(3 * total);
    for (int s = 0; s < frames(); ++s) {
        const std::vector<float> f = readFrame(s);
        all.insert(all.end(), f.begin(), f.end());
    }
    return all;
}

std::uint64_t primitiveFileContentHash(const std::filesystem::path& path)
{
    // Streamed: the same value as checksum64 of the whole file.
    return fileContentHash(path, maxPrimitiveFileBytes(), "primitive file");
}

}  // namespace cg::formats
