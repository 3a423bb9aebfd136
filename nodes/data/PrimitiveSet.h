#pragma once
/// The 3D cloud primitive set of Sec. 4: the positions of the condensed fluid particles of
/// the physical simulation at every primitive frame s. Once a particle appears it stays, with
/// a stable id: frame s holds ids 0..N_f(s)-1 in order of appearance, and N_f(s) never
/// decreases. Positions are relative to the cloud origin (where the cloud first appears: the
/// first cloud particles' mean x and y at their lowest z), in metres.

#include <cstdint>
#include <vector>

#include "core/Data.h"

namespace cg {

class Registry;

class PrimitiveSetData final : public Data {
public:
    /// `counts[s]` = N_f(s); `positions` holds frame 0's N_f(0) xyz triples, then frame 1's,
    /// and so on. Throws std::invalid_argument if the counts decrease or the sizes disagree.
    PrimitiveSetData(double frameTime, std::vector<std::uint32_t> counts,
                     std::vector<float> positions);

    const double frameTime;                   ///< Delta s, seconds of physical time per frame
    const std::vector<std::uint32_t> counts;  ///< N_f(s) for s = 0..frames()-1
    const std::vector<float> positions;       ///< x, y, z per particle per frame, metres

    int frames() const { return static_cast<int>(counts.size()); }
    std::uint32_t count(int s) const { return counts[static_cast<std::size_t>(s)]; }
    /// Pointer to frame s's first xyz triple.
    const float* frame(int s) const
    {
        return positions.data() + 3 * mOffsets[static_cast<std::size_t>(s)];
    }

    /// Particle `id` at fractional frame s (Eq. 11 gives s = A (t - t0)), linearly interpolated
    /// between frames floor(s) and floor(s) + 1; s is clamped to [0, frames() - 1]. Returns
    /// false (and leaves xyz alone) when the particle has not appeared by frame floor(s).
    bool positionAt(double s, std::uint32_t id, float xyz[3]) const;

    std::string typeName() const override { return "PrimitiveSet"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;

private:
    std::vector<std::uint64_t> mOffsets;  ///< first particle of each frame in `positions`
};

void registerPrimitiveSetType(Registry& registry);

}  // namespace cg
