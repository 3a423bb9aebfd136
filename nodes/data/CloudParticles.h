#pragma once
/// Cloud particles of one frame (Sec. 5.2): positions with their recursive level and the id of
/// the source record that made them (provenance, per-level rendering), and where each
/// source's copy stands (surface detail that moves with the copy). Produced by the
/// mapper on demand for each frame, consumed by the voxelizer and the writers.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "algo/mapping/Mapping.h"
#include "core/Data.h"

namespace cg {

class Registry;

/// The highest recursive level a cloud particle can have: PrimitiveMapper's maxLevel is at
/// most this.
inline constexpr int kMaxCloudLevel = 32;

/// What a chunk of cloud particles carries besides the positions.
struct CloudChunkFields {
    bool levels = false;      ///< CloudChunk::levels
    bool sources = false;     ///< CloudChunk::sources, with the frame's copy origins
    bool velocities = false;  ///< CloudChunk::velocities (a stream with motion only)
    bool ids = false;         ///< CloudChunk::ids (a stream with motion only)
};

/// What makes a frame's cloud particles on demand (GenerateCloud's generator), so that a
/// consumer that needs no frame-sized array gets none.
class CloudParticleStream {
public:
    virtual ~CloudParticleStream() = default;
    /// Hands every particle to `consume` once, in chunks: positions always, levels and
    /// sources (with the frame's copy origins) when asked, velocities and ids when asked of a
    /// stream that hasMotion(). Chunks come concurrently from
    /// several threads in no fixed order, so only a consumer whose result does not depend on
    /// the order may use this (the gaussian splat, the copy origin field: integer sums), or
    /// one that places each chunk by its `first` (the PLY writer). The same frame gives the
    /// same chunks (first, count) on every call.
    virtual void forEachChunk(const std::function<void(const algo::CloudChunk&)>& consume,
                              CloudChunkFields fields,
                              const std::function<void()>& checkCancelled) const = 0;
    /// The frame's arrays, particles in order.
    virtual algo::CloudParticleArrays materialise(
        const std::function<void()>& checkCancelled) const = 0;
    /// Whether forEachChunk gives velocities and stable ids when asked.
    virtual bool hasMotion() const { return false; }
};

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
    /// A frame made on demand: streamed to consumers that take chunks, materialised (once,
    /// then kept with the value) for those that read the arrays.
    explicit CloudParticlesData(std::shared_ptr<const CloudParticleStream> stream);

    /// The arrays: the stream's frame is generated on the first call (`checkCancelled` is
    /// called while it is made, and may throw).
    const algo::CloudParticleArrays& arrays(const std::function<void()>& checkCancelled = {}) const;
    /// x, y, z per particle, metres.
    const algo::UninitArray<float>& positions() const { return arrays().positions; }
    /// Recursive level L (1..L_max); 0 for other points.
    const algo::UninitArray<std::uint8_t>& levels() const { return arrays().levels; }
    /// Id of the source record that made each particle.
    const algo::UninitArray<std::uint32_t>& sources() const { return arrays().sources; }
    /// Per source id, x, y, z: where the copy that moves the source's particles stands (Eq.
    /// 12's origin plus its drift), so a particle minus its copy origin is R P_f, its place in
    /// its copy (Eq. 10). Empty for particles that belong to no copy: detail is then in world
    /// coordinates.
    const algo::UninitArray<float>& copyOrigins() const { return arrays().copyOrigins; }
    std::size_t size() const { return levels().size(); }
    /// Whether forEachChunk gives each particle's velocity and stable id (a frame made by the
    /// mapper does; arrays do not hold them).
    bool hasMotion() const;

    /// Hands every particle to `consume` once, in chunks, concurrently and in no fixed order
    /// (see CloudParticleStream): over the arrays once they exist, else from the stream
    /// without a frame-sized array. Levels, sources and copy origins come with the chunks as
    /// `fields` asks; velocities and ids only from a stream with motion (always streamed;
    /// std::invalid_argument without).
    void forEachChunk(const std::function<void(const algo::CloudChunk&)>& consume,
                      CloudChunkFields fields,
                      const std::function<void()>& checkCancelled = {}) const;

    std::string typeName() const override { return "CloudParticles"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;

private:
    std::shared_ptr<const CloudParticleStream> mStream;
    mutable std::once_flag mMade;                  ///< a stream's arrays are made once
    mutable std::atomic<bool> mHaveArrays{false};  ///< mArrays holds the frame
    mutable algo::CloudParticleArrays mArrays;
};

void registerCloudParticlesType(Registry& registry);

}  // namespace cg
