#include "formats/PlyWriter.h"

#include <limits>
#include <stdexcept>

#include "formats/PlyFile.h"

namespace cg::formats {

namespace {

/// PLY ints are signed: refuse what would wrap.
void checkFitsPlyInt(const std::uint32_t* values, std::size_t count, const char* what,
                     const std::filesystem::path& path)
{
    constexpr auto kMax = static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max());
    for (std::size_t i = 0; i < count; ++i)
        if (values[i] > kMax)
            throw std::range_error("cannot write '" + path.string() + "': " + what + " " +
                                   std::to_string(values[i]) + " does not fit a PLY int");
}

}  // namespace

void writeParticlesPly(const std::filesystem::path& path, const PlyParticleView& p,
                       const std::string& comment, const std::function<void()>& poll)
{
    if (p.count > 0 && (!p.x || !p.y || !p.z || !p.vz || !p.temperature || !p.id || !p.homeCell))
        throw std::invalid_argument("writeParticlesPly: a required array is missing");
    checkFitsPlyInt(p.id, p.count, "id", path);
    checkFitsPlyInt(p.homeCell, p.count, "home cell", path);
    writeBinaryPly(path, p.count,
                   {{"x", PlyType::Float, p.x},
                    {"y", PlyType::Float, p.y},
                    {"z", PlyType::Float, p.z},
                    {"vx", PlyType::Float, p.vx},
                    {"vy", PlyType::Float, p.vy},
                    {"vz", PlyType::Float, p.vz},
                    {"temperature", PlyType::Float, p.temperature},
                    {"id", PlyType::Int, p.id},  // checked above: the bits are the same
                    {"state", PlyType::Int, p.state},
                    {"home_cell", PlyType::Int, p.homeCell}},
                   comment, poll);
}

}  // namespace cg::formats
