#include "formats/PlyFile.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "util/LittleEndian.h"

namespace cg::formats {

namespace {

constexpr std::size_t kChunkBytes = std::size_t{1} << 20;  // records per write: about 1 MiB

std::size_t sizeOf(PlyType t) { return t == PlyType::UChar ? 1 : 4; }

const char* nameOf(PlyType t)
{
    switch (t) {
        case PlyType::Float:
            return "float";
        case PlyType::Int:
            return "int";
        case PlyType::UInt:
            return "uint";
        case PlyType::UChar:
            return "uchar";
    }
    return "";
}

/// Packs element i of `p` at `out`, little-endian.
void pack(const PlyProperty& p, std::size_t i, unsigned char* out)
{
    const std::size_t at = i * p.stride;
    switch (p.type) {
        case PlyType::Float:
            util::putF32(out, p.data ? static_cast<const float*>(p.data)[at] : 0.0f);
            break;
        case PlyType::Int:
            util::putU32(out, static_cast<std::uint32_t>(
                                  p.data ? static_cast<const std::int32_t*>(p.data)[at] : 0));
            break;
        case PlyType::UInt:
            util::putU32(out, p.data ? static_cast<const std::uint32_t*>(p.data)[at] : 0u);
            break;
        case PlyType::UChar:
            *out = p.data ? static_cast<const std::uint8_t*>(p.data)[at] : std::uint8_t{0};
            break;
    }
}

[[noreturn]] void writeFailed(const std::filesystem::path& path)
{
    // Streams need not set errno; say so rather than print "Success".
    const int e = errno;
    throw std::runtime_error("cannot write '" + path.string() +
                             "': " + (e != 0 ? std::strerror(e) : "I/O error"));
}

}  // namespace

std::string binaryPlyHeader(std::size_t count, const std::vector<PlyProperty>& properties,
                            const std::string& comment)
{
    std::string line = comment;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::replace(line.begin(), line.end(), '\r', ' ');
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment CloudGraph";
    if (!line.empty()) header += " " + line;
    header += "\nelement vertex " + std::to_string(count) + "\n";
    for (const PlyProperty& p : properties)
        header += std::string("property ") + nameOf(p.type) + " " + p.name + "\n";
    return header + "end_header\n";
}

std::size_t plyRecordBytes(const std::vector<PlyProperty>& properties)
{
    std::size_t bytes = 0;
    for (const PlyProperty& p : properties) bytes += sizeOf(p.type);
    return bytes;
}

void packPlyRecords(const std::vector<PlyProperty>& properties, std::size_t begin, std::size_t end,
                    unsigned char* out)
{
    for (std::size_t i = begin; i < end; ++i)
        for (const PlyProperty& p : properties) {
            pack(p, i, out);
            out += sizeOf(p.type);
        }
}

void writeBinaryPly(const std::filesystem::path& path, std::size_t count,
                    const std::vector<PlyProperty>& properties, const std::string& comment,
                    const std::function<void()>& poll)
{
    const std::string header = binaryPlyHeader(count, properties, comment);
    const std::size_t recordBytes = plyRecordBytes(properties);

    errno = 0;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) writeFailed(path);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));

    const std::size_t perChunk =
        std::max<std::size_t>(1, kChunkBytes / std::max<std::size_t>(1, recordBytes));
    std::vector<unsigned char> chunk(std::min(count, perChunk) * recordBytes);
    for (std::size_t begin = 0; begin < count && out; begin += perChunk) {
        if (poll) poll();
        const std::size_t end = std::min(count, begin + perChunk);
        packPlyRecords(properties, begin, end, chunk.data());
        out.write(reinterpret_cast<const char*>(chunk.data()),
                  static_cast<std::streamsize>((end - begin) * recordBytes));
    }
    out.close();
    if (!out) writeFailed(path);
}

}  // namespace cg::formats
