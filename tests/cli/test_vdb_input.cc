// VDB inputs that `run` refuses are refused by `validate` too, and a valid VDB whose active
// voxels lie too far apart for the renderer's dense grids is bad input naming the node, never a
// crash.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "support/TestUtil.h"

namespace cg {

using test::runCli;
using test::TempDir;

TEST(CliVdbInput, AVolumeWhoseVoxelsLieTooFarApartIsRefusedByTheRendererNotACrash)
{
    // Two active voxels 2^25 - 24 voxels apart on x and 2^24 - 24 on y and z: the renderer's
    // occupancy grid would have 2^22 x 2^21 x 2^21 blocks, 2^64, which wraps to 0 in 64 bits.
    TempDir dir;
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->tree().setValue({0, 0, 0}, 0.5f);
    grid->tree().setValue({(1 << 25) - 24, (1 << 24) - 24, (1 << 24) - 24}, 0.5f);
    {
        // Without the bounding box OpenVDB records by default: only the Renderer can tell.
        openvdb::io::File file((dir / "unrecorded.vdb").string());
        file.setGridStatsMetadataEnabled(false);
        file.write({grid});
    }
    openvdb::io::File((dir / "recorded.vdb").string()).write({grid});
    const std::string extents = "4194304 x 2097152 x 2097152 blocks";

    for (const std::string name : {"unrecorded", "recorded"}) {
        for (const std::string mode : {"fast", "pathtrace"}) {
            test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "nodes": {
                "read": {"type": "ReadVDB", "params": {"file": ")" +
                                                name + R"(.vdb"}},
                "render": {"type": "Renderer", "inputs": {"volume": "read.volume"},
                           "params": {"width": 16, "height": 12, "mode": ")" +
                                                mode + R"("}}}})");
            const auto r =
                runCli({"run", (dir / "g.json").string(), "--out", (dir / "out").string()});
            EXPECT_EQ(r.exitCode, 2) << name << " " << mode << ": " << r.errors;
            // The Renderer when it cooks; ReadVDB's file as the graph loads, from the box the
            // file records.
            EXPECT_NE(r.errors.find(name == "unrecorded" ? "g.json:/nodes/render"
                                                         : "g.json:/nodes/read/params/file"),
                      std::string::npos)
                << r.errors;
            EXPECT_NE(r.errors.find(extents), std::string::npos) << r.errors;
            EXPECT_EQ(r.errors.find("internal error"), std::string::npos) << r.errors;
        }
        // validate reads the voxels too: it refuses both.
        const auto v = runCli({"validate", (dir / "g.json").string()});
        EXPECT_EQ(v.exitCode, 2) << name << ": " << v.errors;
        EXPECT_NE(v.errors.find("g.json:/nodes/read/params/file"), std::string::npos) << v.errors;
        EXPECT_NE(v.errors.find(extents), std::string::npos) << v.errors;
    }
}

}  // namespace cg
