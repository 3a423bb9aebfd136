// VapourEmitter and WriteParticles in graphs: outputs, files on disk, and refused input.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "algo/atmosphere/VapourEmission.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/io/IoNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

/// The ramp the TestRampMap node makes: cell c of n has density scale * c / (n - 1).
std::vector<float> rampValues(std::int64_t nx, std::int64_t ny, double scale)
{
    const auto n = static_cast<std::size_t>(nx * ny);
    std::vector<float> v(n, 0.0f);
    for (std::size_t c = 0; n > 1 && c < n; ++c)
        v[c] = static_cast<float>(scale * static_cast<double>(c) / static_cast<double>(n - 1));
    return v;
}

class TestRampMapNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        const std::int64_t nx = p.getInt("nx");
        const std::int64_t ny = p.getInt("ny");
        ctx.setOutput("map", std::make_shared<Map2DData>(static_cast<int>(nx), static_cast<int>(ny),
                                                         p.getFloat("cellSize"),
                                                         rampValues(nx, ny, p.getFloat("scale"))));
    }
};

/// A fixed Map2D source, standing in for NoiseMap.
void registerTestRampMap(Registry& registry)
{
    NodeDecl d;
    d.type = "TestRampMap";
    d.category = "test";
    d.doc = "a row-major ramp 0..scale over nx x ny cells";
    d.outputs = {port("map", "Map2D", "the ramp")};
    d.params = {intParam("nx", 6, "cells", "columns", 1, 1e6),
                intParam("ny", 4, "cells", "rows", 1, 1e6),
                floatParam("cellSize", 10.0, "m", "cell edge", 1e-3, 1e6),
                floatParam("scale", 1.0, "", "density of the last cell", 0.0, 10.0)};
    d.create = [] { return std::make_unique<TestRampMapNode>(); };
    registry.addNode(std::move(d));
}

/// The records of a binary little-endian PLY whose properties are all 4 bytes wide.
struct PlyRecords {
    std::vector<std::string> names;
    std::vector<std::vector<double>> rows;
    double at(std::size_t row, const std::string& name) const
    {
        for (std::size_t i = 0; i < names.size(); ++i)
            if (names[i] == name) return rows.at(row).at(i);
        throw std::runtime_error("no property " + name);
    }
};

PlyRecords readPly(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path.string());
    PlyRecords ply;
    std::vector<bool> isFloat;
    std::size_t count = 0;
    std::string line;
    std::getline(in, line);
    if (line != "ply") throw std::runtime_error("not a PLY");
    std::getline(in, line);
    if (line != "format binary_little_endian 1.0") throw std::runtime_error(line);
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream words(line);
        std::string keyword, a, b;
        words >> keyword >> a >> b;
        if (keyword == "element") count = std::stoul(b);
        if (keyword == "property") {
            isFloat.push_back(a == "float");
            ply.names.push_back(b);
        }
    }
    std::vector<unsigned char> buf(4 * ply.names.size());
    for (std::size_t r = 0; r < count; ++r) {
        if (!in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(buf.size())))
            throw std::runtime_error("truncated");
        std::vector<double> row;
        for (std::size_t i = 0; i < ply.names.size(); ++i) {
            std::uint32_t bits = 0;
            for (int k = 3; k >= 0; --k)
                bits = bits << 8 | buf[4 * i + static_cast<std::size_t>(k)];
            float f;
            std::memcpy(&f, &bits, sizeof f);
            row.push_back(isFloat[i] ? static_cast<double>(f)
                                     : static_cast<double>(static_cast<std::int32_t>(bits)));
        }
        ply.rows.push_back(std::move(row));
    }
    if (in.peek() != std::char_traits<char>::eof()) throw std::runtime_error("trailing bytes");
    return ply;
}

class VapourEmitterNodeTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerVapourEmitterNode(registry);
        registerWriteParticlesNode(registry);
        registerTestRampMap(registry);
    }

    Graph parse(const std::string& emitterParams, const std::string& mapParams = "{}")
    {
        return parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 2}, "nodes": {
            "map": {"type": "TestRampMap", "params": )" +
                              mapParams + R"(},
            "emit": {"type": "VapourEmitter", "params": )" +
                              emitterParams + R"(, "inputs": {"map": "map.map"}},
            "write": {"type": "WriteParticles", "params": {"file": "out/name.####.ply"},
                      "inputs": {"particles": "emit.particles"}}}})",
                          "test.json", registry);
    }

    std::shared_ptr<const VapourParticlesData> emitted(Evaluator& ev, const Graph& g, int frame)
    {
        return std::dynamic_pointer_cast<const VapourParticlesData>(
            ev.pull(g, "emit", frame)->at("particles"));
    }

    Registry registry;
};

}  // namespace

TEST_F(VapourEmitterNodeTest, OutputIsTheEmissionOfTheMap)
{
    const Graph g = parse(R"({"maxParticlesPerCell": 9, "minParticlesPerCell": 1, "seed": 3,
                              "minHeight": 10, "maxHeight": 510})",
                          R"({"nx": 7, "ny": 5, "cellSize": 20})");
    Evaluator ev(registry, {});
    const auto p = emitted(ev, g, 0);
    ASSERT_TRUE(p);

    algo::VapourEmissionSettings s;
    s.minParticlesPerCell = 1;
    s.maxParticlesPerCell = 9;
    s.minHeight = 10;
    s.maxHeight = 510;
    s.seed = 3;
    const std::vector<float> values = rampValues(7, 5, 1.0);
    const algo::VapourEmission e = algo::emitVapour(7, 5, 20.0, values, s);
    ASSERT_EQ(p->size(), algo::emissionCount(values, s));
    EXPECT_EQ(p->statics->id, e.id);
    EXPECT_EQ(p->statics->homeCell, e.homeCell);
    EXPECT_EQ(p->statics->x, e.x);
    EXPECT_EQ(p->statics->y, e.y);
    EXPECT_EQ(p->z, e.z);
    EXPECT_EQ(p->vz, e.vz);
    EXPECT_EQ(p->temperature, e.temperature);

    // Emission is at t0 only: one key for the whole animation.
    EXPECT_EQ(ev.key(g, "emit", 0), ev.key(g, "emit", 2));
}

TEST_F(VapourEmitterNodeTest, WriteParticlesWritesAReadablePlyPerFrame)
{
    test::TempDir dir;
    const Graph g = parse("{}");
    EvaluatorOptions options;
    options.outDir = dir.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 0, 1);

    const auto p = emitted(ev, g, 0);
    ASSERT_GT(p->size(), 0u);
    for (const char* name : {"out/name.0000.ply", "out/name.0001.ply"}) {
        SCOPED_TRACE(name);
        const PlyRecords ply = readPly(dir / name);
        const std::vector<std::string> names = {"x",  "y",           "z",  "vx",    "vy",
                                                "vz", "temperature", "id", "state", "home_cell"};
        EXPECT_EQ(ply.names, names);
        ASSERT_EQ(ply.rows.size(), p->size());
        for (std::size_t i = 0; i < p->size(); ++i) {
            ASSERT_EQ(ply.at(i, "x"), p->statics->x[i]);
            ASSERT_EQ(ply.at(i, "y"), p->statics->y[i]);
            ASSERT_EQ(ply.at(i, "z"), p->z[i]);
            ASSERT_EQ(ply.at(i, "vx"), 0.0);  // emitted: nothing has moved them yet
            ASSERT_EQ(ply.at(i, "vz"), p->vz[i]);
            ASSERT_EQ(ply.at(i, "temperature"), p->temperature[i]);
            ASSERT_EQ(ply.at(i, "id"), p->statics->id[i]);
            ASSERT_EQ(ply.at(i, "state"), 0.0);
            ASSERT_EQ(ply.at(i, "home_cell"), p->statics->homeCell[i]);
        }
    }
    // Nothing but the two files (no temp file left behind).
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "out")) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 2u);
}

TEST_F(VapourEmitterNodeTest, WriteParticlesHonoursEvery)
{
    test::TempDir dir;
    Graph g = parse("{}");
    g.setParam("write", "every", 2);
    EvaluatorOptions options;
    options.outDir = dir.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 0, 2);
    EXPECT_TRUE(std::filesystem::exists(dir / "out/name.0000.ply"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out/name.0001.ply"));
    EXPECT_TRUE(std::filesystem::exists(dir / "out/name.0002.ply"));
}

TEST_F(VapourEmitterNodeTest, WriterMarksCondensedParticles)
{
    test::TempDir dir;
    auto statics = std::make_shared<VapourStatics>();
    statics->id = {0, 1, 2, 3};
    statics->homeCell = {0, 0, 1, 5};
    statics->x = {0.5f, 1.5f, 2.5f, 3.5f};
    statics->y = {1.0f, 2.0f, 3.0f, 4.0f};
    statics->startZ = {0.0f, 0.0f, 0.0f, 0.0f};
    auto particles = std::make_shared<VapourParticlesData>(
        statics, std::vector<float>{10, 20, 30, 40}, std::vector<float>{0.5f, 0, -1, 2},
        std::vector<float>{29, 28, 27, 26});
    auto condensation =
        std::make_shared<CondensationData>(particles, std::vector<std::int32_t>{-1, 3, -1, 0},
                                           std::vector<float>{NAN, 20, NAN, 40}, 0);

    const NodeDecl* decl = registry.findNode("WriteParticles");
    ASSERT_TRUE(decl);
    ParamSet params(&decl->params);
    EvalContext eval;
    eval.frame = 7;
    {
        CookContext ctx(*decl, "write", params, eval, dir.path());
        ctx.setInput("particles", particles);
        ctx.setInput("condensation", condensation);
        decl->create()->cook(ctx);
        const auto out = ctx.takeOutputs();
        const auto files = std::dynamic_pointer_cast<const TextData>(out.at("files"));
        ASSERT_TRUE(files);
        EXPECT_EQ(files->value, (dir / "particles.0007.ply").string());
    }
    const PlyRecords ply = readPly(dir / "particles.0007.ply");
    ASSERT_EQ(ply.rows.size(), 4u);
    const std::vector<double> state = {0, 1, 0, 1};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(ply.at(i, "state"), state[i]) << i;
        EXPECT_EQ(ply.at(i, "vz"), particles->vz[i]) << i;
        EXPECT_EQ(ply.at(i, "home_cell"), statics->homeCell[i]) << i;
    }

    // Condensation of other particles than the ones written is refused, naming the node.
    auto fewer = std::make_shared<VapourStatics>();
    fewer->id = {0};
    fewer->homeCell = {0};
    fewer->x = {0.5f};
    fewer->y = {0.5f};
    fewer->startZ = {0.0f};
    auto one = std::make_shared<VapourParticlesData>(fewer, std::vector<float>{1},
                                                     std::vector<float>{0}, std::vector<float>{3});
    CookContext ctx(*decl, "write", params, eval, dir.path());
    ctx.setInput("particles", one);
    ctx.setInput("condensation", condensation);
    try {
        decl->create()->cook(ctx);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "write");
        EXPECT_NE(e.message().find("condensation"), std::string::npos) << e.what();
    }
}

TEST_F(VapourEmitterNodeTest, InvertedRangesAreRefusedAtLoad)
{
    struct Case {
        const char* params;
        const char* param;
    };
    for (const Case& c :
         {Case{R"({"minHeight": 200, "maxHeight": 100})", "maxHeight"},
          Case{R"({"minParticlesPerCell": 5, "maxParticlesPerCell": 4})", "maxParticlesPerCell"},
          Case{R"({"minTemperature": 31})", "maxTemperature"}}) {
        SCOPED_TRACE(c.params);
        try {
            parse(c.params);
            FAIL() << "expected InputError";
        } catch (const InputError& e) {
            EXPECT_NE(e.where().find(std::string("/nodes/emit/params/") + c.param),
                      std::string::npos)
                << e.what();
        }
    }
    EXPECT_NO_THROW(parse(R"({"minHeight": 100, "maxHeight": 100})"));
}

TEST_F(VapourEmitterNodeTest, TooManyParticlesAreRefusedBeforeAllocating)
{
    // About 1e9 particles (28 GB): refused at cook time, naming the parameter.
    const Graph g = parse(R"({"maxParticlesPerCell": 1000000})", R"({"nx": 2000, "ny": 1})");
    Evaluator ev(registry, {});
    try {
        ev.pull(g, "emit", 0);
        FAIL() << "expected a CookError";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        EXPECT_EQ(e.nodeId(), "emit");
        EXPECT_NE(std::string(e.what()).find("maxParticlesPerCell"), std::string::npos) << e.what();
    }
}

TEST_F(VapourEmitterNodeTest, DensityOutsideUnitRangeIsBadInput)
{
    const Graph g = parse("{}", R"({"scale": 2})");
    Evaluator ev(registry, {});
    try {
        ev.pull(g, "emit", 0);
        FAIL() << "expected a CookError";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        EXPECT_NE(std::string(e.what()).find("input 'map'"), std::string::npos) << e.what();
    }
}

}  // namespace cg
