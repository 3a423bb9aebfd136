#include "nodes/data/FogVolume.h"

#include <sstream>
#include <stdexcept>

#include <openvdb/io/Stream.h>

#include "core/Registry.h"

namespace cg {

FogVolumeData::FogVolumeData(openvdb::FloatGrid::ConstPtr grid_) : grid(std::move(grid_))
{
    if (!grid) throw std::invalid_argument("FogVolume: null grid");
}

std::size_t FogVolumeData::byteSize() const { return sizeof(*this) + grid->memUsage(); }

bool FogVolumeData::serialize(ByteWriter& out) const
{
    std::ostringstream stream(std::ios::binary);
    openvdb::GridCPtrVec grids{grid};
    openvdb::io::Stream(stream).write(grids);
    out.str(stream.str());
    return true;
}

void registerFogVolumeType(Registry& registry)
{
    openvdb::initialize();
    registry.addDataType({"FogVolume", "an OpenVDB fog volume (FloatGrid 'density', values in [0, 1])",
                          [](ByteReader& in) -> DataPtr {
                              std::istringstream stream(in.str(), std::ios::binary);
                              openvdb::io::Stream vdb(stream);
                              const openvdb::GridPtrVecPtr grids = vdb.getGrids();
                              if (!grids || grids->size() != 1)
                                  throw std::runtime_error("FogVolume: expected one grid");
                              auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>((*grids)[0]);
                              if (!grid) throw std::runtime_error("FogVolume: not a FloatGrid");
                              return std::make_shared<FogVolumeData>(grid);
                          }});
}

}  // namespace cg
