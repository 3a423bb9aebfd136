#pragma once
/// Cloud particles of one frame (Sec. 5.2): positions with their recursive level and the id of
/// the source record that made them (provenance, per-level rendering), and where each
/// source's copy stands (surface detail that moves with the copy). Produced by the
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
    /// copyOrigins is empty or holds 3 floats for every source id a particle names
    /// (std::invalid_argument otherwise).
    CloudParticlesData(algo::UninitArray<float> positions, algo::UninitArray<std::uint8_t> levels,
                       algo::UninitArray<std::uint32_t> sources,
                       algo::UninitArray<float> copyOrigins = {});
    /// Copies the arrays.
    CloudParticlesData(const std::vector<float>& positions, const std::vector<std::uint8_t>& levels,
                       const std::vector<std::uint32_t>& sources,
                       const std::vector<float>& copyOrigins = {});

    // Read like const std::vectors (data(), size(), begin()/end(), []) and convert to one.
    const algo::UninitArray<float> positions;          ///< x, y, z per particle, metres
    const algo::UninitArray<std::uint8_t> levels;      ///< recursive level L (1..L_max); 0 for other points
    const algo::UninitArray<std::uint32_t> sources;    ///< id of the source record that made it
    /// Per source id, x, y, z: where the copy that moves the source's particles stands (Eq. 12's
    /// origin plus its drift), so a particle minus its copy origin is R P_f, its place in its
    /// copy (Eq. 10). Empty for particles that belong to no copy: detail is then in world
    /// coordinates.
    const algo::UninitArray<float> copyOrigins;

    std::size_t size() const { return levels.size(); }

    std::string typeName() const override { return "CloudParticles"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;
};

void registerCloudParticlesType(Registry& registry);

}  // namespace cg
