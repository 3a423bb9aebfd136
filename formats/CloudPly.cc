#include "formats/CloudPly.h"

#include "formats/PlyFile.h"

namespace cg::formats {

void writeCloudPly(const std::filesystem::path& path, std::size_t count, const float* positions,
                   const std::uint8_t* levels, const std::uint32_t* sources,
                   const std::string& comment, const std::function<void()>& poll)
{
    writeBinaryPly(path, count,
                   {{"x", PlyType::Float, positions, 3},
                    {"y", PlyType::Float, count ? positions + 1 : nullptr, 3},
                    {"z", PlyType::Float, count ? positions + 2 : nullptr, 3},
                    {"level", PlyType::UChar, levels},
                    {"source", PlyType::UInt, sources}},
                   comment, poll);
}

}  // namespace cg::formats
