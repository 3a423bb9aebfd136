#include "nodes/data/VapourParticles.h"

#include <algorithm>
#include <stdexcept>

#include "core/Registry.h"

namespace cg {

VapourParticlesData::VapourParticlesData(std::shared_ptr<const VapourStatics> statics_,
                                         std::vector<float> z_, std::vector<float> vz_,
                                         std::vector<float> temperature_)
    : statics(std::move(statics_)), z(std::move(z_)), vz(std::move(vz_)),
      temperature(std::move(temperature_))
{
    const std::size_t n = statics ? statics->size() : 0;
    if (!statics || statics->homeCell.size() != n || statics->x.size() != n ||
        statics->y.size() != n || z.size() != n || vz.size() != n || temperature.size() != n)
        throw std::invalid_argument("VapourParticles: arrays differ in length");
}

std::size_t VapourParticlesData::byteSize() const
{
    // The statics are shared across frames; count them anyway, as a cache cannot know.
    return sizeof(*this) + sizeof(VapourStatics) + size() * (4 * 4 + 3 * 4);
}

bool VapourParticlesData::serialize(ByteWriter& out) const
{
    out.podVector(statics->id);
    out.podVector(statics->homeCell);
    out.podVector(statics->x);
    out.podVector(statics->y);
    out.podVector(z);
    out.podVector(vz);
    out.podVector(temperature);
    return true;
}

std::shared_ptr<const VapourParticlesData> VapourParticlesData::deserialize(ByteReader& in)
{
    auto statics = std::make_shared<VapourStatics>();
    statics->id = in.podVector<std::uint32_t>();
    statics->homeCell = in.podVector<std::uint32_t>();
    statics->x = in.podVector<float>();
    statics->y = in.podVector<float>();
    auto z = in.podVector<float>();
    auto vz = in.podVector<float>();
    auto t = in.podVector<float>();
    return std::make_shared<VapourParticlesData>(std::move(statics), std::move(z), std::move(vz),
                                                 std::move(t));
}

CondensationData::CondensationData(std::shared_ptr<const VapourParticlesData> particles_,
                                   std::vector<std::int32_t> condensedFrame_, std::int32_t firstFrame_)
    : particles(std::move(particles_)), condensedFrame(std::move(condensedFrame_)), firstFrame(firstFrame_)
{
    if (!particles || condensedFrame.size() != particles->size())
        throw std::invalid_argument("Condensation: arrays differ in length");
}

std::size_t CondensationData::condensedCount() const
{
    return static_cast<std::size_t>(
        std::count_if(condensedFrame.begin(), condensedFrame.end(), [](std::int32_t f) { return f >= 0; }));
}

std::size_t CondensationData::byteSize() const
{
    return sizeof(*this) + condensedFrame.size() * sizeof(std::int32_t) + particles->byteSize();
}

bool CondensationData::serialize(ByteWriter& out) const
{
    particles->serialize(out);
    out.podVector(condensedFrame);
    out.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(firstFrame)));
    return true;
}

void registerVapourParticleTypes(Registry& registry)
{
    registry.addDataType({"VapourParticles",
                          "water vapour particles: id, home cell, x, y, height, vertical velocity, "
                          "temperature",
                          [](ByteReader& in) -> DataPtr { return VapourParticlesData::deserialize(in); }});
    registry.addDataType({"Condensation",
                          "vapour particles with the frame at which each condensed, and the "
                          "first condensation frame",
                          [](ByteReader& in) -> DataPtr {
                              auto particles = VapourParticlesData::deserialize(in);
                              auto frames = in.podVector<std::int32_t>();
                              const auto first = static_cast<std::int32_t>(static_cast<std::int64_t>(in.u64()));
                              return std::make_shared<CondensationData>(std::move(particles),
                                                                        std::move(frames), first);
                          }});
}

}  // namespace cg
