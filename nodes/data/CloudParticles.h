#pragma once
/// Cloud particles of one frame (Sec. 5.2): positions with their recursive level and the id of
/// the source record that made them (provenance, per-level rendering). Produced by the
/// mapper on demand for each frame, consumed by the voxelizer and the writers.

#include <cstdint>
#include <vector>

#include "algo/mapping/Mapping.h"
#include "core/Data.h"

namespace cg {

class Registry;

/// The highest recursive level a cloud particle can have: PrimitiveMapper's maxLevel is at
/// most this.
inline constexpr int kMaxCloudLevel = 32;

class CloudParticlesData final : public Data {
public:
    /// Takes the arrays (GenerateCloud's fresh frame arrays, filled in parallel, never zeroed).
    CloudParticlesData(algo::UninitArray<float> positions, algo::UninitArray<std::uint8_t> levels,
                       algo::UninitArray<std::uint32_t> sources);
    /// Copies the arrays.
    CloudParticlesData(const std::vector<float>& positions, const std::vector<std::uint8_t>& levels,
                       const std::vector<std::uint32_t>& sources);

    // Read like const std::vectors (data(), size(), begin()/end(), []) and convert to one.
    const algo::UninitArray<float> positions;          ///< x, y, z per particle, metres
    const algo::UninitArray<std::uint8_t> levels;      ///< recursive level L (1..L_max); 0 for other points
    const algo::UninitArray<std::uint32_t> sources;    ///< id of the source record that made it

    std::size_t size() const { return levels.size(); }

    std::string typeName() const override { return "CloudParticles"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;
};

void registerCloudParticlesType(Registry& registry);

}  // namespace cg
