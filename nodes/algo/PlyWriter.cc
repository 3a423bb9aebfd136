#include "nodes/algo/PlyWriter.h"
#include "util/LittleEndian.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <vector>

namespace cg::algo {

namespace {

constexpr std::size_t kRecordsPerChunk = 1 << 15;  // 1 MiB of records per write

using util::putU32;
const auto putFloat = util::putF32;

void putInt(unsigned char* p, std::int32_t v) { putU32(p, static_cast<std::uint32_t>(v)); }

std::int32_t asPlyInt(std::uint32_t v, const char* what, const std::filesystem::path& path)
{
    if (v > static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max()))
        throw std::range_error("cannot write '" + path.string() + "': " + what + " " +
                               std::to_string(v) + " does not fit a PLY int");
    return static_cast<std::int32_t>(v);
}

[[noreturn]] void writeFailed(const std::filesystem::path& path)
{
    // Streams need not set errno; say so rather than print "Success".
    const int e = errno;
    throw std::runtime_error("cannot write '" + path.string() +
                             "': " + (e != 0 ? std::strerror(e) : "I/O error"));
}

}  // namespace

void writeParticlesPly(const std::filesystem::path& path, const PlyParticleView& p,
                       const std::string& comment, const std::function<void()>& poll)
{
    if (p.count > 0 && (!p.x || !p.y || !p.z || !p.vz || !p.temperature || !p.id || !p.homeCell))
        throw std::invalid_argument("writeParticlesPly: a required array is missing");

    std::string line = comment;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::replace(line.begin(), line.end(), '\r', ' ');
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment CloudGraph";
    if (!line.empty()) header += " " + line;
    header += "\nelement vertex " + std::to_string(p.count) +
              "\n"
              "property float x\n"
              "property float y\n"
              "property float z\n"
              "property float vz\n"
              "property float temperature\n"
              "property int id\n"
              "property int state\n"
              "property int home_cell\n"
              "end_header\n";

    errno = 0;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) writeFailed(path);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));

    std::vector<unsigned char> chunk(std::min(p.count, kRecordsPerChunk) * kPlyRecordBytes);
    for (std::size_t begin = 0; begin < p.count && out; begin += kRecordsPerChunk) {
        if (poll) poll();
        const std::size_t end = std::min(p.count, begin + kRecordsPerChunk);
        unsigned char* r = chunk.data();
        for (std::size_t i = begin; i < end; ++i, r += kPlyRecordBytes) {
            putFloat(r + 0, p.x[i]);
            putFloat(r + 4, p.y[i]);
            putFloat(r + 8, p.z[i]);
            putFloat(r + 12, p.vz[i]);
            putFloat(r + 16, p.temperature[i]);
            putInt(r + 20, asPlyInt(p.id[i], "id", path));
            putInt(r + 24, p.state ? p.state[i] : 0);
            putInt(r + 28, asPlyInt(p.homeCell[i], "home cell", path));
        }
        out.write(reinterpret_cast<const char*>(chunk.data()),
                  static_cast<std::streamsize>((end - begin) * kPlyRecordBytes));
    }
    out.close();
    if (!out) writeFailed(path);
}

}  // namespace cg::algo
