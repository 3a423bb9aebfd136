#include "nodes/algo/CloudPly.h"
#include "util/LittleEndian.h"

#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace cg::algo {

namespace {

using util::putU32;

}  // namespace

void writeCloudPly(const std::filesystem::path& path, std::size_t count, const float* positions,
                   const std::uint8_t* levels, const std::uint32_t* sources,
                   const std::string& comment, const std::function<void()>& poll)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    std::string oneLine = comment;
    for (char& c : oneLine)
        if (c == '\n' || c == '\r') c = ' ';
    out << "ply\nformat binary_little_endian 1.0\ncomment CloudGraph " << oneLine
        << "\nelement vertex " << count
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar level\n"
           "property uint source\nend_header\n";
    constexpr std::size_t kRecord = 17;
    constexpr std::size_t kChunk = 65536;
    std::vector<unsigned char> buffer(kChunk * kRecord);
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
        if (poll) poll();
        const std::size_t end = std::min(count, begin + kChunk);
        unsigned char* p = buffer.data();
        for (std::size_t i = begin; i < end; ++i, p += kRecord) {
            for (int k = 0; k < 3; ++k) {
                std::uint32_t bits;
                std::memcpy(&bits, &positions[3 * i + static_cast<std::size_t>(k)], 4);
                putU32(p + 4 * k, bits);
            }
            p[12] = levels[i];
            putU32(p + 13, sources[i]);
        }
        out.write(reinterpret_cast<const char*>(buffer.data()),
                  static_cast<std::streamsize>((end - begin) * kRecord));
    }
    out.close();
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
}

}  // namespace cg::algo
