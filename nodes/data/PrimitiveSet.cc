#include "nodes/data/PrimitiveSet.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "PrimitiveSet";

DataPtr readPrimitiveSet(ByteReader& in)
{
    const double frameTime = in.f64();
    auto counts = in.podVector<std::uint32_t>();
    auto positions = in.podVector<float>();
    // Every producer (PrimitiveSim, the .cgp reader) makes at least one frame, a finite frame
    // time and finite positions; the mapper reads frame count - 1 and divides by the time.
    if (!std::isfinite(frameTime)) checks::refuse(kType, "frame time is not finite");
    if (counts.empty()) checks::refuse(kType, "no frames");
    if (counts.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        checks::refuse(kType, std::to_string(counts.size()) + " frames do not fit an int");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i]))
            checks::refuse(kType, "coordinate " + std::to_string(i) + " is not finite");
    // The constructor checks that the counts never decrease and match the positions.
    return std::make_shared<PrimitiveSetData>(frameTime, std::move(counts), std::move(positions));
}

}  // namespace

PrimitiveSetData::PrimitiveSetData(double frameTime_, std::vector<std::uint32_t> counts_,
                                   std::vector<float> positions_)
    : frameTime(frameTime_), counts(std::move(counts_)), positions(std::move(positions_))
{
    if (!(frameTime > 0.0))
        throw std::invalid_argument("PrimitiveSet: frame time must be positive");
    mOffsets.reserve(counts.size());
    // Bounded by the positions as it grows, so a huge sum of counts cannot wrap around.
    const std::uint64_t particles = positions.size() / 3;
    std::uint64_t total = 0;
    for (std::size_t s = 0; s < counts.size(); ++s) {
        if (s > 0 && counts[s] < counts[s - 1])
            throw std::invalid_argument("PrimitiveSet: N_f(s) decreases at frame " +
                                        std::to_string(s));
        mOffsets.push_back(total);
        total += counts[s];
        if (total > particles) break;
    }
    if (total != particles || positions.size() % 3 != 0)
        throw std::invalid_argument("PrimitiveSet: positions do not match the counts");
}

bool PrimitiveSetData::positionAt(double s, std::uint32_t id, float xyz[3]) const
{
    if (counts.empty()) return false;
    const double last = static_cast<double>(counts.size() - 1);
    if (!(s > 0.0)) s = 0.0;  // also catches NaN
    if (s > last) s = last;
    const auto s0 = static_cast<int>(s);
    if (id >= count(s0)) return false;
    const float* a = frame(s0) + 3 * std::size_t{id};
    if (s0 + 1 >= frames()) {
        for (int k = 0; k < 3; ++k) xyz[k] = a[k];
        return true;
    }
    const float* b = frame(s0 + 1) + 3 * std::size_t{id};  // N_f never decreases: id is there
    const auto f = static_cast<float>(s - s0);
    for (int k = 0; k < 3; ++k) xyz[k] = a[k] + f * (b[k] - a[k]);
    return true;
}

std::size_t PrimitiveSetData::byteSize() const
{
    return sizeof(*this) + positions.size() * sizeof(float) + counts.size() * 12;
}

bool PrimitiveSetData::serialize(ByteWriter& out) const
{
    out.f64(frameTime);
    out.podVector(counts);
    out.podVector(positions);
    return true;
}

void registerPrimitiveSetType(Registry& registry)
{
    registry.addDataType(
        {"PrimitiveSet", "the 3D cloud primitive set: condensed fluid particle positions per frame",
         readPrimitiveSet});
}

}  // namespace cg
