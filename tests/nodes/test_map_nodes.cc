// Maps an artist paints: ReadMap reads WriteMap's files back (PFM bit for bit, PNG to 16
// bits), paintings in 8-bit, RGB and EXR with WriteMap's orientation, refuses what is not a
// map; MapMath's operations against their closed forms; and a painted ring makes a field
// whose condensation particles stand over the ring.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/ExrFile.h"
#include "formats/MapImage.h"
#include "formats/PngFile.h"
#include "nodes/Builtin.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/VapourParticles.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

class MapNodesTest : public ::testing::Test {
protected:
    void SetUp() override { registerBuiltinNodes(registry); }

    Graph parse(const std::string& nodes, const std::string& frames = "")
    {
        return parseGraph(R"({"cloudgraph": 1, )" + frames + R"("nodes": {)" + nodes + "}}",
                          (dir / "g.json").string(), registry);
    }

    std::shared_ptr<const Map2DData> map(const Graph& g, const std::string& node)
    {
        EvaluatorOptions options;
        options.outDir = dir.path();
        Evaluator ev(registry, options);
        return std::dynamic_pointer_cast<const Map2DData>(ev.pull(g, node, 0)->at("map"));
    }

    std::shared_ptr<const Map2DData> read(const std::filesystem::path& file,
                                          const std::string& extra = "")
    {
        return map(parse(R"("read": {"type": "ReadMap", "params": {"file": ")" + file.string() +
                         R"(", "cellSize": 25)" + extra + "}}"),
                   "read");
    }

    /// `mapNodes`, then vapour emitted from `map` (with `emitParams`), risen and condensed
    /// over frames 0-20 of 2 s.
    /// `emitInputs`: more of the emitter's inputs, each `, "port": "node.output"`.
    Graph field(const std::string& mapNodes, const std::string& map,
                const std::string& emitParams = "", const std::string& emitInputs = "")
    {
        return parse(mapNodes + R"(,
            "atmosphere": {"type": "Atmosphere"},
            "emit": {"type": "VapourEmitter", "inputs": {"map": ")" +
                         map + "\"" + emitInputs + R"(}, "params": {)" + emitParams + R"(}},
            "rise": {"type": "ThermalIntegrator", "inputs": {"particles": "emit.particles",
                     "atmosphere": "atmosphere.atmosphere"}},
            "condense": {"type": "Condensation", "inputs": {"particles": "rise.particles",
                         "atmosphere": "atmosphere.atmosphere"}})",
                     R"("frames": {"start": 0, "end": 20}, "timeStep": 2.0, )");
    }

    /// An 8-bit PNG of `channels` samples a pixel, rows top first.
    void png8(const std::filesystem::path& file, int w, int h, int channels,
              const std::vector<unsigned char>& samples)
    {
        std::vector<const unsigned char*> rows;
        for (int r = 0; r < h; ++r)
            rows.push_back(&samples[static_cast<std::size_t>(r * w * channels)]);
        formats::writePng(file.string(), w, h, channels, 8, rows, false);
    }

    test::TempDir dir;
    Registry registry;
};

/// A 5 x 3 ramp with distinct values, iy = 0 the bottom row.
std::vector<float> ramp()
{
    std::vector<float> v;
    for (int i = 0; i < 15; ++i) v.push_back(static_cast<float>(i) / 14.0f * 0.999f + 1e-4f);
    return v;
}

}  // namespace

TEST_F(MapNodesTest, ReadMapReadsWriteMapsFilesBack)
{
    const std::vector<float> values = ramp();
    formats::writePfm((dir / "m.pfm").string(), 5, 3, values);
    formats::writePng16((dir / "m.png").string(), 5, 3, values);
    const auto pfm = read(dir / "m.pfm");
    EXPECT_EQ(pfm->nx, 5);
    EXPECT_EQ(pfm->ny, 3);
    EXPECT_EQ(pfm->cellSize, 25.0);
    EXPECT_EQ(pfm->values, values);  // bit for bit
    const auto png = read(dir / "m.png");
    ASSERT_EQ(png->values.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        EXPECT_NEAR(png->values[i], values[i], 0.5 / 65535.0 + 1e-7) << i;
}

TEST_F(MapNodesTest, PaintingsAreReadTheWayUpTheyWerePainted)
{
    // A white pixel at the image's top-left corner is the map's cell (0, ny - 1).
    std::vector<unsigned char> grey(4 * 3, 0);
    grey[0] = 255;
    grey[4 * 3 - 1] = 51;  // bottom-right: cell (3, 0)
    png8(dir / "grey.png", 4, 3, 1, grey);
    const auto g = read(dir / "grey.png");
    EXPECT_EQ(g->at(0, 2), 1.0f);
    EXPECT_FLOAT_EQ(g->at(3, 0), 0.2f);
    EXPECT_EQ(g->at(0, 0), 0.0f);

    // RGB: the Rec. 709 luminance of the stored values.
    std::vector<unsigned char> rgb(2 * 1 * 3, 0);
    rgb[0] = 255;  // pure red
    rgb[4] = 255;  // pure green
    png8(dir / "rgb.png", 2, 1, 3, rgb);
    const auto c = read(dir / "rgb.png");
    EXPECT_NEAR(c->at(0, 0), 0.2126f, 1e-6);
    EXPECT_NEAR(c->at(1, 0), 0.7152f, 1e-6);

    // EXR: its Y channel, top row first in the file.
    const std::vector<float> y = {0.25f, 0.5f, 0.75f, 1.0f};
    formats::writeExrFloat32((dir / "y.exr").string(), 2, 2, {{{"Y"}, y}});
    const auto e = read(dir / "y.exr");
    EXPECT_EQ(e->at(0, 1), 0.25f);
    EXPECT_EQ(e->at(1, 0), 1.0f);
}

TEST_F(MapNodesTest, WhatIsNotAMapIsRefusedNamingTheFile)
{
    const auto refusal = [&](const std::filesystem::path& file, const std::string& extra = "") {
        try {
            read(file, extra);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    std::ofstream(dir / "notes.txt") << "not a picture";
    EXPECT_NE(refusal(dir / "notes.txt").find("not a PNG, PFM or OpenEXR"), std::string::npos);
    EXPECT_NE(refusal(dir / "notes.txt").find("read/params/file"), std::string::npos);
    formats::writePfm((dir / "hot.pfm").string(), 2, 1, {0.5f, 1.5f});
    const std::string hot = refusal(dir / "hot.pfm");
    EXPECT_NE(hot.find("cell (1, 0) is 1.5"), std::string::npos) << hot;
    EXPECT_EQ(read(dir / "hot.pfm", R"(, "outOfRange": "clamp")")->at(1, 0), 1.0f);
    formats::writePfm((dir / "nan.pfm").string(), 2, 1, {0.5f, std::nanf("")});
    EXPECT_NE(refusal(dir / "nan.pfm").find("not finite"), std::string::npos);
    EXPECT_NE(refusal(dir / "missing.png").find("missing.png"), std::string::npos);
}

TEST_F(MapNodesTest, MapMathOperationsAreTheirClosedForms)
{
    // a: 4 x 2 cells of 100 m; b: 2 x 1 cells of 200 m holding 0.2 and 0.6, read bilinearly
    // between its centres at x = 100 m and 300 m.
    formats::writePfm((dir / "a.pfm").string(), 4, 2,
                      {0.1f, 0.4f, 0.7f, 1.0f, 0.0f, 0.5f, 0.5f, 0.9f});
    formats::writePfm((dir / "b.pfm").string(), 2, 1, {0.2f, 0.6f});
    const auto op = [&](const std::string& params) {
        return map(
            parse(R"("a": {"type": "ReadMap", "params": {"file": ")" + (dir / "a.pfm").string() +
                  R"(", "cellSize": 100}},
            "b": {"type": "ReadMap", "params": {"file": ")" +
                  (dir / "b.pfm").string() +
                  R"(", "cellSize": 200}},
            "m": {"type": "MapMath", "inputs": {"a": "a.map", "b": "b.map"}, "params": {)" +
                  params + "}}"),
            "m");
    };
    // a's centres x = 50, 150, 250, 350: b there = 0.2, 0.3, 0.5, 0.6.
    const auto product = op(R"("op": "multiply")");
    EXPECT_NEAR(product->at(0, 0), 0.1 * 0.2, 1e-6);
    EXPECT_NEAR(product->at(1, 0), 0.4 * 0.3, 1e-6);
    EXPECT_NEAR(product->at(2, 1), 0.5 * 0.5, 1e-6);
    EXPECT_NEAR(product->at(3, 1), 0.9 * 0.6, 1e-6);
    EXPECT_EQ(op(R"("op": "add")")->at(3, 1), 1.0f);  // 1.5 clamped
    EXPECT_EQ(op(R"("op": "subtract")")->at(0, 0), 0.0f);
    EXPECT_NEAR(op(R"("op": "invert")")->at(1, 0), 0.6, 1e-6);
    const auto step = op(R"("op": "threshold", "threshold": 0.5)");
    EXPECT_EQ(step->at(1, 0), 0.0f);
    EXPECT_EQ(step->at(1, 1), 1.0f);
    EXPECT_NEAR(op(R"("op": "remap", "low": 0.1, "high": 0.5, "gamma": 2)")->at(1, 0),
                std::pow(0.75, 2.0), 1e-6);
    // Blur: a constant map stays constant (edges renormalised); a wide blur pulls every
    // value toward the mean.
    const auto blurred = op(R"("op": "blur", "blurRadius": 100000)");
    for (float v : blurred->values) EXPECT_NEAR(v, 0.5125, 1e-3);
    try {
        op(R"("op": "remap", "low": 0.5, "high": 0.5)");
        ADD_FAILURE() << "remap with high == low accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("high"), std::string::npos);
    }
}

TEST_F(MapNodesTest, APaintedRingMakesCloudOverTheRing)
{
    // A 32 x 32 painting of a ring 8-12 cells from the centre; vapour rises from it and
    // condenses: at least 90% of the condensation particles stand over painted cells.
    const int n = 32;
    std::vector<unsigned char> ring(static_cast<std::size_t>(n * n), 0);
    for (int r = 0; r < n; ++r)
        for (int x = 0; x < n; ++x) {
            const double d = std::hypot(x + 0.5 - n / 2.0, r + 0.5 - n / 2.0);
            if (d >= 8 && d <= 12) ring[static_cast<std::size_t>(r * n + x)] = 255;
        }
    png8(dir / "ring.png", n, n, 1, ring);
    const Graph g = field(R"("paint": {"type": "ReadMap", "params": {"file": ")" +
                              (dir / "ring.png").string() + R"(", "cellSize": 50}})",
                          "paint.map");
    EvaluatorOptions options;
    options.outDir = dir.path();
    Evaluator ev(registry, options);
    const auto c = std::dynamic_pointer_cast<const CondensationData>(
        ev.pull(g, "condense", 20)->at("condensation"));
    const auto m = map(g, "paint");
    std::size_t condensed = 0, overRing = 0;
    for (std::size_t i = 0; i < c->particles->size(); ++i) {
        if (!c->condensed(i)) continue;
        ++condensed;
        const std::int64_t cell = m->cellAt(c->particles->xs()[i], c->particles->ys()[i]);
        if (m->values[static_cast<std::size_t>(cell)] > 0.5f) ++overRing;
    }
    EXPECT_GT(condensed, 100u);
    EXPECT_GE(overRing, condensed * 9 / 10) << overRing << " of " << condensed;
}

TEST_F(MapNodesTest, AHeroCloudGrowsWhereItIsPlacedAndWhenItIsTold)
{
    // A map with no vapour anywhere (the noise remapped to 0) and one hero at (600, 900) m,
    // radius 250 m, starting 10 s in: the vapour rises there alone, and only after 10 s.
    const Graph g = field(R"("noise": {"type": "NoiseMap", "params": {"width": 32, "height": 32}},
        "none": {"type": "MapMath", "inputs": {"a": "noise.map"},
                 "params": {"op": "remap", "low": 5, "high": 6}})",
                          "none.map", R"("heroClouds": [600, 900, 250, 10])");
    EvaluatorOptions options;
    options.outDir = dir.path();
    Evaluator ev(registry, options);
    const auto start = std::dynamic_pointer_cast<const VapourParticlesData>(
        ev.pull(g, "emit", 0)->at("particles"));
    ASSERT_GT(start->size(), 50u);
    for (std::size_t i = 0; i < start->size(); ++i)
        ASSERT_LE(std::hypot(start->xs()[i] - 600.0, start->ys()[i] - 900.0), 250.0 + 50.0);
    // Frame 4 is 8 s in: nothing has left its start yet.
    const auto early = std::dynamic_pointer_cast<const VapourParticlesData>(
        ev.pull(g, "rise", 4)->at("particles"));
    for (std::size_t i = 0; i < early->size(); ++i) ASSERT_EQ(early->z[i], start->z[i]) << i;
    const auto c = std::dynamic_pointer_cast<const CondensationData>(
        ev.pull(g, "condense", 20)->at("condensation"));
    EXPECT_GT(c->condensedCount(), 50u);
    EXPECT_GT(c->firstFrame, 5);
    // The emitter's map output is the hero: 1 at its centre, 0 beyond its radius.
    const auto m = std::dynamic_pointer_cast<const Map2DData>(ev.pull(g, "emit", 0)->at("map"));
    EXPECT_EQ(m->values[static_cast<std::size_t>(m->cellAt(600, 900))], 1.0f);
    EXPECT_EQ(m->values[static_cast<std::size_t>(m->cellAt(600, 1200))], 0.0f);
}

TEST_F(MapNodesTest, AStartDelayMapStartsCloudsWhereAndWhenItSays)
{
    // The noise's east half (x >= 800 m) painted white, delayed 12 s: at frame 5 (10 s) its
    // vapour still waits at its start while the west half's has risen; by frame 20 both have.
    png8(dir / "late.png", 2, 1, 1, {0, 255});
    const Graph g = field(R"("noise": {"type": "NoiseMap", "params": {"width": 32, "height": 32}},
        "late": {"type": "ReadMap", "params": {"file": ")" +
                              (dir / "late.png").string() + R"(", "cellSize": 800}})",
                          "noise.map", R"("startDelayMax": 12)", R"(, "startDelay": "late.map")");
    EvaluatorOptions options;
    options.outDir = dir.path();
    Evaluator ev(registry, options);
    const auto at = [&](int frame) {
        return std::dynamic_pointer_cast<const VapourParticlesData>(
            ev.pull(g, "rise", frame)->at("particles"));
    };
    const auto start = at(0), early = at(5), late = at(20);
    std::size_t east = 0, westRisen = 0, eastRisenLate = 0;
    for (std::size_t i = 0; i < start->size(); ++i) {
        if (start->xs()[i] >= 800.0f) {
            ++east;
            ASSERT_EQ(early->z[i], start->z[i]) << i;
            eastRisenLate += late->z[i] > start->z[i];
        } else {
            westRisen += early->z[i] > start->z[i];
        }
    }
    ASSERT_GT(east, 100u);
    EXPECT_GT(westRisen, 100u);
    EXPECT_EQ(eastRisenLate, east);
}

}  // namespace cg
