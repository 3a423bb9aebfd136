#pragma once
/// The mapper's state: the table of source records (Sec. 5.2) and the settings that place
/// their clusters, so cloud particles can be generated from it at any frame.

#include <memory>
#include <vector>

#include "algo/mapping/Mapping.h"
#include "core/Data.h"

namespace cg {

class Registry;
class CondensationData;
class PrimitiveSetData;

class CloudSourcesData final : public Data {
public:
    CloudSourcesData(algo::SourceTable sourceTable, algo::MappingSettings mappingSettings)
        : table(std::move(sourceTable)), settings(std::move(mappingSettings))
    {
    }
    const algo::SourceTable table;
    const algo::MappingSettings settings;

    std::string typeName() const override { return "CloudSources"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;
};

/// The ranges of PrimitiveMapper's parameters: the node declares them from here, and stored
/// settings outside them are refused.
struct MappingLimits {
    static constexpr std::size_t kMaxListSize = 32;      ///< selectionRatio, windowLength
    static constexpr std::int64_t kMaxFrames = 1000000;  ///< firstStart, levelDelay, windows
    static constexpr double kMaxCoefficient = 1e3;       ///< R0, A0
    static constexpr double kMinMetres = 1e-6, kMaxMetres = 1e6;  ///< metresPerPrimitiveMetre
    static constexpr double kMaxTimeStep = 86400.0;               ///< the graph's timeStep, seconds
    static constexpr std::int64_t kMaxSources = 1000000000;
    static constexpr std::uint64_t kMaxParticlesPerCopy = std::uint64_t{1} << 30;
    static constexpr double kMaxTrailRiseSpeed = 100.0;  ///< m/s
};

/// Throws std::runtime_error unless `table` and `s` are a state PrimitiveMapper could have
/// made, checking everything the mapping algorithm relies on that they hold alone: settings
/// in the node's ranges; records in order of their start frames, each with its level in
/// 1..L_max, its parent an earlier record of the level below, finite A >= 1 and R >= 0 within
/// Eq. 16's reach; the taken-candidate sets exactly those of the records (selection's probing
/// relies on a free candidate); t_s[L] per level. O(records + candidates taken).
void checkSourceTable(const algo::SourceTable& table, const algo::MappingSettings& s);

/// Throws std::runtime_error unless `table`, mapped with settings `s`, can be read against
/// these inputs: every level-1 record's parent is a condensation particle that had condensed
/// when the record started, and every deeper record's parent fluid particle exists in the
/// primitive when it started (so at every later frame). The deserializer cannot check this
/// (the inputs are other values): consumers of a stored table call it before mapping, with
/// the settings they map with (GenerateCloud the table's own; PrimitiveMapper, stepping from
/// its previous frame, its parameters'). O(records).
void checkSourcesFit(const algo::SourceTable& table, const algo::MappingSettings& s,
                     const CondensationData& condensation,
                     const std::vector<std::shared_ptr<const PrimitiveSetData>>& primitives);
/// The same for a table made with one primitive set.
void checkSourcesFit(const algo::SourceTable& table, const algo::MappingSettings& s,
                     const CondensationData& condensation, const PrimitiveSetData& primitive);

void registerCloudSourcesType(Registry& registry);

}  // namespace cg
