#pragma once
/// The mapper's state: the table of source records (Sec. 5.2) and the settings that place
/// their clusters, so cloud particles can be generated from it at any frame.

#include "core/Data.h"
#include "nodes/algo/Mapping.h"

namespace cg {

class Registry;

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

void registerCloudSourcesType(Registry& registry);

}  // namespace cg
