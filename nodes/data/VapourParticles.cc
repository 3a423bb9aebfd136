#include "nodes/data/VapourParticles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

/// What the emitter guarantees and the statics never lose: ids 0..N-1 in emission order,
/// emitted cell by cell in row-major order, at finite x, y on the map (corner at the origin).
/// Heights, velocities and temperatures are not checked: the explicit integrator may
/// honestly overflow them, and their consumers (condensation's comparison, the voxelizer's
/// finiteness check, the writers) cope.
void checkStatics(const VapourStatics& s, const char* type)
{
    for (std::size_t i = 0; i < s.id.size(); ++i) {
        if (s.id[i] != i)
            checks::refuse(type,
                           "particle " + std::to_string(i) + " has id " + std::to_string(s.id[i]));
        if (i > 0 && s.homeCell[i] < s.homeCell[i - 1])
            checks::refuse(type,
                           "home cells are not in emission order at particle " + std::to_string(i));
        if (!(s.x[i] >= 0.0f && s.y[i] >= 0.0f) || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
            checks::refuse(type, "particle " + std::to_string(i) + " is not on the map");
        // Consumers look the start height up in a profile and add the offset to a dew point.
        if (!std::isfinite(s.startZ[i]) ||
            (!s.dewpointOffset.empty() && !std::isfinite(s.dewpointOffset[i])) ||
            (!s.releaseTime.empty() &&
             !(s.releaseTime[i] >= 0.0f && std::isfinite(s.releaseTime[i]))))
            checks::refuse(type, "particle " + std::to_string(i) + " has no finite start");
    }
}

std::shared_ptr<const VapourParticlesData> readParticles(ByteReader& in, const char* type)
{
    auto statics = std::make_shared<VapourStatics>();
    statics->id = in.podVector<std::uint32_t>();
    statics->homeCell = in.podVector<std::uint32_t>();
    statics->x = in.podVector<float>();
    statics->y = in.podVector<float>();
    statics->startZ = in.podVector<float>();
    statics->dewpointOffset = in.podVector<float>();
    statics->releaseTime = in.podVector<float>();
    auto z = in.podVector<float>();
    auto vz = in.podVector<float>();
    auto t = in.podVector<float>();
    auto x = in.podVector<float>();
    auto y = in.podVector<float>();
    auto vx = in.podVector<float>();
    auto vy = in.podVector<float>();
    const std::size_t n = statics->id.size();
    const auto emptyOrN = [n](const std::vector<float>& v) { return v.empty() || v.size() == n; };
    if (statics->homeCell.size() != n || statics->x.size() != n || statics->y.size() != n ||
        statics->startZ.size() != n || !emptyOrN(statics->dewpointOffset) ||
        !emptyOrN(statics->releaseTime) || z.size() != n || vz.size() != n || t.size() != n ||
        !emptyOrN(x) || x.size() != y.size() || !emptyOrN(vx) || vx.size() != vy.size())
        checks::refuse(type, "particle arrays differ in length");  // before checkStatics reads them
    checkStatics(*statics, type);
    return std::make_shared<VapourParticlesData>(std::move(statics), std::move(x), std::move(y),
                                                 std::move(vx), std::move(vy), std::move(z),
                                                 std::move(vz), std::move(t));
}

/// Condensation frames are -1 (still vapour) or the frame a particle condensed, with a finite
/// height exactly when it condensed, and the first condensation frame is the earliest of them
/// (-1 while there is none).
DataPtr readCondensation(ByteReader& in)
{
    constexpr const char* kType = "Condensation";
    auto particles = readParticles(in, kType);
    auto frames = in.podVector<std::int32_t>();
    auto heights = in.podVector<float>();
    const auto first = static_cast<std::int32_t>(
        checks::intIn(in.u64(), -1, checks::kMaxFrame, kType, "first frame"));
    std::int64_t earliest = -1;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        if (frames[i] < -1 || frames[i] > checks::kMaxFrame)
            checks::refuse(kType, "particle " + std::to_string(i) + " condensed at frame " +
                                      std::to_string(frames[i]));
        if (frames[i] >= 0 && (earliest < 0 || frames[i] < earliest)) earliest = frames[i];
        if (i < heights.size() && std::isfinite(heights[i]) != (frames[i] >= 0))
            checks::refuse(kType, "particle " + std::to_string(i) + " has condensation height " +
                                      std::to_string(heights[i]) + " at condensation frame " +
                                      std::to_string(frames[i]));
    }
    if (first != earliest)
        checks::refuse(kType, "first condensation frame " + std::to_string(first) +
                                  " but the earliest is " + std::to_string(earliest));
    // The constructor checks that there is one frame and one height per particle.
    return std::make_shared<CondensationData>(std::move(particles), std::move(frames),
                                              std::move(heights), first);
}

}  // namespace

VapourParticlesData::VapourParticlesData(std::shared_ptr<const VapourStatics> statics_,
                                         std::vector<float> z_, std::vector<float> vz_,
                                         std::vector<float> temperature_)
    : VapourParticlesData(std::move(statics_), {}, {}, std::move(z_), std::move(vz_),
                          std::move(temperature_))
{
}

VapourParticlesData::VapourParticlesData(std::shared_ptr<const VapourStatics> statics_,
                                         std::vector<float> x_, std::vector<float> y_,
                                         std::vector<float> z_, std::vector<float> vz_,
                                         std::vector<float> temperature_)
    : VapourParticlesData(std::move(statics_), std::move(x_), std::move(y_), {}, {}, std::move(z_),
                          std::move(vz_), std::move(temperature_))
{
}

VapourParticlesData::VapourParticlesData(std::shared_ptr<const VapourStatics> statics_,
                                         std::vector<float> x_, std::vector<float> y_,
                                         std::vector<float> vx_, std::vector<float> vy_,
                                         std::vector<float> z_, std::vector<float> vz_,
                                         std::vector<float> temperature_)
    : statics(std::move(statics_)),
      z(std::move(z_)),
      vz(std::move(vz_)),
      temperature(std::move(temperature_)),
      mX(std::move(x_)),
      mY(std::move(y_)),
      mVx(std::move(vx_)),
      mVy(std::move(vy_))
{
    const std::size_t n = statics ? statics->size() : 0;
    if (!statics || statics->homeCell.size() != n || statics->x.size() != n ||
        statics->y.size() != n || statics->startZ.size() != n ||
        (!statics->dewpointOffset.empty() && statics->dewpointOffset.size() != n) ||
        (!statics->releaseTime.empty() && statics->releaseTime.size() != n) || z.size() != n ||
        vz.size() != n || temperature.size() != n || (!mX.empty() && mX.size() != n) ||
        mY.size() != mX.size() || (!mVx.empty() && mVx.size() != n) || mVy.size() != mVx.size())
        throw std::invalid_argument("VapourParticles: arrays differ in length");
}

std::size_t VapourParticlesData::byteSize() const
{
    // The statics are shared across frames; count them anyway, as a cache cannot know.
    return sizeof(*this) + sizeof(VapourStatics) + size() * (5 * 4 + 3 * 4) +
           (statics->dewpointOffset.size() + statics->releaseTime.size() + mX.size() + mY.size() +
            mVx.size() + mVy.size()) *
               4;
}

bool VapourParticlesData::serialize(ByteWriter& out) const
{
    out.podVector(statics->id);
    out.podVector(statics->homeCell);
    out.podVector(statics->x);
    out.podVector(statics->y);
    out.podVector(statics->startZ);
    out.podVector(statics->dewpointOffset);
    out.podVector(statics->releaseTime);
    out.podVector(z);
    out.podVector(vz);
    out.podVector(temperature);
    out.podVector(mX);
    out.podVector(mY);
    out.podVector(mVx);
    out.podVector(mVy);
    return true;
}

std::shared_ptr<const VapourParticlesData> VapourParticlesData::deserialize(ByteReader& in)
{
    return readParticles(in, "VapourParticles");
}

CondensationData::CondensationData(std::shared_ptr<const VapourParticlesData> particles_,
                                   std::vector<std::int32_t> condensedFrame_,
                                   std::vector<float> condensedHeight_, std::int32_t firstFrame_)
    : particles(std::move(particles_)),
      condensedFrame(std::move(condensedFrame_)),
      condensedHeight(std::move(condensedHeight_)),
      firstFrame(firstFrame_)
{
    if (!particles || condensedFrame.size() != particles->size() ||
        condensedHeight.size() != particles->size())
        throw std::invalid_argument("Condensation: arrays differ in length");
}

std::size_t CondensationData::condensedCount() const
{
    return static_cast<std::size_t>(std::count_if(condensedFrame.begin(), condensedFrame.end(),
                                                  [](std::int32_t f) { return f >= 0; }));
}

std::size_t CondensationData::byteSize() const
{
    return sizeof(*this) + condensedFrame.size() * sizeof(std::int32_t) +
           condensedHeight.size() * sizeof(float) + particles->byteSize();
}

bool CondensationData::serialize(ByteWriter& out) const
{
    particles->serialize(out);
    out.podVector(condensedFrame);
    out.podVector(condensedHeight);
    out.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(firstFrame)));
    return true;
}

void registerVapourParticleTypes(Registry& registry)
{
    registry.addDataType(
        {"VapourParticles",
         "water vapour particles: id, home cell, start position and moisture, "
         "height, vertical velocity, temperature, and x, y and their velocity once moved",
         [](ByteReader& in) -> DataPtr { return VapourParticlesData::deserialize(in); }});
    registry.addDataType({"Condensation",
                          "vapour particles with the frame at which each condensed, and the "
                          "first condensation frame",
                          readCondensation});
}

}  // namespace cg
