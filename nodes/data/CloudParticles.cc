#include "nodes/data/CloudParticles.h"

#include <stdexcept>
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
    // Positions may honestly be non-finite (so may the condensation particles they grow
    // from): the voxelizer refuses those itself. Source ids are provenance only.
    for (std::size_t i = 0; i < levels.size(); ++i)
        if (levels[i] > kMaxCloudLevel)
            checks::refuse("CloudParticles", "particle " + std::to_string(i) + " has level " +
                                                 std::to_string(levels[i]));
    // The constructor checks that the arrays agree in length.
    return std::make_shared<CloudParticlesData>(std::move(positions), std::move(levels),
                                                std::move(sources));
}

}  // namespace

CloudParticlesData::CloudParticlesData(algo::UninitArray<float> positions_, algo::UninitArray<std::uint8_t> levels_,
                                       algo::UninitArray<std::uint32_t> sources_)
    : positions(std::move(positions_)), levels(std::move(levels_)), sources(std::move(sources_))
{
    if (positions.size() != 3 * levels.size() || sources.size() != levels.size())
        throw std::invalid_argument("CloudParticles: arrays differ in length");
}

CloudParticlesData::CloudParticlesData(const std::vector<float>& positions_,
                                       const std::vector<std::uint8_t>& levels_,
                                       const std::vector<std::uint32_t>& sources_)
    : CloudParticlesData(algo::UninitArray<float>(positions_), algo::UninitArray<std::uint8_t>(levels_),
                         algo::UninitArray<std::uint32_t>(sources_))
{
}

std::size_t CloudParticlesData::byteSize() const
{
    return sizeof(*this) + positions.size() * sizeof(float) + levels.size() + sources.size() * 4;
}

bool CloudParticlesData::serialize(ByteWriter& out) const
{
    writeArray(out, positions);
    writeArray(out, levels);
    writeArray(out, sources);
    return true;
}

void registerCloudParticlesType(Registry& registry)
{
    registry.addDataType({"CloudParticles",
                          "cloud particles of one frame: position, level, source id",
                          readCloudParticles});
}

}  // namespace cg
