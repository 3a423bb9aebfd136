#include "nodes/data/CloudParticles.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

template <class T>
void writeArray(ByteWriter& out, const algo::UninitArray<T>& a)
{
    out.u64(a.size());  // the layout of ByteWriter::podVector
    out.bytes(a.data(), a.size() * sizeof(T));
}

template <class T>
algo::UninitArray<T> readArray(ByteReader& in)
{
    if (in.remaining() < sizeof(std::uint64_t)) checks::refuse("CloudParticles", "truncated payload");
    const std::uint64_t n = in.u64();
    if (n > in.remaining() / sizeof(T)) checks::refuse("CloudParticles", "truncated payload");
    algo::UninitArray<T> a(static_cast<std::size_t>(n));
    in.bytes(a.data(), a.size() * sizeof(T));
    return a;
}

DataPtr readCloudParticles(ByteReader& in)
{
    auto positions = readArray<float>(in);
    auto levels = readArray<std::uint8_t>(in);
    auto sources = readArray<std::uint32_t>(in);
    auto copyOrigins = readArray<float>(in);
    // Positions may honestly be non-finite (so may the condensation particles they grow
    // from): the voxelizer refuses those itself, and so copy origins.
    for (std::size_t i = 0; i < levels.size(); ++i)
        if (levels[i] > kMaxCloudLevel)
            checks::refuse("CloudParticles", "particle " + std::to_string(i) + " has level " +
                                                 std::to_string(levels[i]));
    // The constructor checks that the arrays agree in length and every source has an origin.
    return std::make_shared<CloudParticlesData>(std::move(positions), std::move(levels),
                                                std::move(sources), std::move(copyOrigins));
}

}  // namespace

CloudParticlesData::CloudParticlesData(algo::UninitArray<float> positions_, algo::UninitArray<std::uint8_t> levels_,
                                       algo::UninitArray<std::uint32_t> sources_,
                                       algo::UninitArray<float> copyOrigins_)
    : positions(std::move(positions_)), levels(std::move(levels_)), sources(std::move(sources_)),
      copyOrigins(std::move(copyOrigins_))
{
    if (positions.size() != 3 * levels.size() || sources.size() != levels.size())
        throw std::invalid_argument("CloudParticles: arrays differ in length");
    if (copyOrigins.size() % 3 != 0)
        throw std::invalid_argument("CloudParticles: copy origins are not xyz triples");
    if (!copyOrigins.empty()) {
        const std::size_t copies = copyOrigins.size() / 3;
        for (std::size_t i = 0; i < sources.size(); ++i)
            if (sources[i] >= copies)
                throw std::invalid_argument("CloudParticles: particle " + std::to_string(i) + " names source " +
                                            std::to_string(sources[i]) + ", which has no copy origin");
    }
}

CloudParticlesData::CloudParticlesData(const std::vector<float>& positions_,
                                       const std::vector<std::uint8_t>& levels_,
                                       const std::vector<std::uint32_t>& sources_,
                                       const std::vector<float>& copyOrigins_)
    : CloudParticlesData(algo::UninitArray<float>(positions_), algo::UninitArray<std::uint8_t>(levels_),
                         algo::UninitArray<std::uint32_t>(sources_), algo::UninitArray<float>(copyOrigins_))
{
}

std::size_t CloudParticlesData::byteSize() const
{
    return sizeof(*this) + positions.size() * sizeof(float) + levels.size() + sources.size() * 4 +
           copyOrigins.size() * sizeof(float);
}

bool CloudParticlesData::serialize(ByteWriter& out) const
{
    writeArray(out, positions);
    writeArray(out, levels);
    writeArray(out, sources);
    writeArray(out, copyOrigins);
    return true;
}

void registerCloudParticlesType(Registry& registry)
{
    registry.addDataType({"CloudParticles",
                          "cloud particles of one frame: position, level, source id; the copy origin of each source",
                          readCloudParticles});
}

}  // namespace cg
