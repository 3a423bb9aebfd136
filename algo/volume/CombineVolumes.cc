#include "algo/volume/CombineVolumes.h"

#include <cstdio>
#include <string>

#include <openvdb/tools/Composite.h>

namespace cg::algo {

namespace {

std::string metres(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g m", v);
    return text;
}

}  // namespace

CombineMode combineModeFromName(const std::string& name)
{
    if (name == "max") return CombineMode::Max;
    if (name == "sum") return CombineMode::Sum;
    throw std::invalid_argument("unknown combine mode '" + name + "' (max, sum)");
}

openvdb::FloatGrid::Ptr combineFogVolumes(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b,
                                          CombineMode mode)
{
    if (a.transform() != b.transform())
        throw std::invalid_argument(
            "the volumes have different transforms (voxel size " + metres(a.voxelSize()[0]) +
            " against " + metres(b.voxelSize()[0]) + "): give both Voxelizers the same voxelSize");
    // The composite operators take their operands' trees: work on copies.
    openvdb::FloatGrid::Ptr out = a.deepCopy();
    openvdb::FloatGrid::Ptr other = b.deepCopy();
    if (mode == CombineMode::Max) {
        openvdb::tools::compMax(*out, *other);
    } else {
        openvdb::tools::compSum(*out, *other);
        openvdb::tools::foreach (out->beginValueOn(),
                                 [](const openvdb::FloatGrid::ValueOnIter& it) {
                                     if (*it > 1.0f) it.setValue(1.0f);
                                 });
    }
    out->setName("density");
    out->setGridClass(openvdb::GRID_FOG_VOLUME);
    return out;
}

}  // namespace cg::algo
