// Engine tests with fixture nodes that count their cooks or fail on purpose.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <stdexcept>

#include <tbb/global_control.h>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "formats/FormatError.h"
#include "nodes/Builtin.h"
#include "nodes/DeclHelpers.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

class EvaluatorTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerBuiltinNodes(registry);
        registerFixtureNodes(registry);
        resetCookCounts();
    }

    Graph parse(const std::string& text) { return parseGraph(text, "test.json", registry); }

    /// Registers TestAdd again as `type`, stored where the flags say.
    void addTestAddCopy(const std::string& type, bool cacheOnDisk, bool cacheInMemory)
    {
        NodeDecl copy = *registry.findNode("TestAdd");
        copy.type = type;
        copy.cacheOnDisk = cacheOnDisk;
        copy.cacheInMemory = cacheInMemory;
        registry.addNode(copy);
    }

    std::vector<float> values(const OutputsPtr& out, const std::string& port)
    {
        return std::dynamic_pointer_cast<const FloatArrayData>(out->at(port))->values;
    }

    /// Registers `type`, a node whose cook calls `body` (which throws).
    void addThrowingNode(const std::string& type, std::function<void(CookContext&)> body)
    {
        struct Impl final : Node {
            explicit Impl(std::function<void(CookContext&)> f) : fn(std::move(f)) {}
            void cook(CookContext& ctx) override { fn(ctx); }
            std::function<void(CookContext&)> fn;
        };
        NodeDecl d;
        d.type = type;
        d.category = "test";
        d.doc = "throws on purpose";
        d.outputs = {port("values", "FloatArray", "never set")};
        d.create = [body] { return std::make_unique<Impl>(body); };
        registry.addNode(d);
    }

    Registry registry;
};

const char* kChain = R"({
  "cloudgraph": 1,
  "frames": {"start": 0, "end": 0},
  "nodes": {
    "n1": {"type": "TestSource", "params": {"value": 1}},
    "n2": {"type": "TestAdd", "inputs": {"values": "n1.values"}},
    "n3": {"type": "TestAdd", "inputs": {"values": "n2.values"}},
    "n4": {"type": "TestAdd", "inputs": {"values": "n3.values"}},
    "n5": {"type": "TestAdd", "inputs": {"values": "n4.values"}}
  }
})";

}  // namespace

TEST_F(EvaluatorTest, ChainCooksOnceThenHitsTheCache)
{
    Graph g = parse(kChain);
    Evaluator ev(registry, {});
    EXPECT_EQ(values(ev.pull(g, "n5", 0), "values"), std::vector<float>(4, 5.0f));
    for (const char* id : {"n1", "n2", "n3", "n4", "n5"}) EXPECT_EQ(cookCount(id), 1u) << id;
    ev.pull(g, "n5", 0);
    EXPECT_EQ(totalCookCount(), 5u);
}

TEST_F(EvaluatorTest, EditingNode3RecooksExactly3To5)
{
    Graph g = parse(kChain);
    Evaluator ev(registry, {});
    ev.pull(g, "n5", 0);
    resetCookCounts();
    ev.report().clear();

    g.setParam("n3", "add", 10.0);
    EXPECT_EQ(values(ev.pull(g, "n5", 0), "values"), std::vector<float>(4, 14.0f));
    EXPECT_EQ(cookCount("n1"), 0u);
    EXPECT_EQ(cookCount("n2"), 0u);
    EXPECT_EQ(cookCount("n3"), 1u);
    EXPECT_EQ(cookCount("n4"), 1u);
    EXPECT_EQ(cookCount("n5"), 1u);
    // The report says why each one cooked.
    for (const CookRecord& r : ev.report().records()) {
        if (r.node == "n3") {
            EXPECT_EQ(r.reason, "parameter 'add' changed (1 -> 10)");
        }
        if (r.node == "n4") {
            EXPECT_EQ(r.reason, "input 'values' changed");
        }
        if (r.node == "n1") {
            EXPECT_EQ(r.status, CookStatus::MemoryHit);
        }
    }

    // Setting it back is a cache hit everywhere: keys are content hashes.
    resetCookCounts();
    g.setParam("n3", "add", 1.0);
    ev.pull(g, "n5", 0);
    EXPECT_EQ(totalCookCount(), 0u);
}

TEST_F(EvaluatorTest, KeysChangeWithParametersAndIgnoreNodeIds)
{
    Graph g = parse(kChain);
    Evaluator ev(registry, {});
    const Key before = ev.key(g, "n5", 0);
    g.setParam("n1", "count", 5);
    EXPECT_NE(ev.key(g, "n5", 0), before);
    g.setParam("n1", "count", 4);
    EXPECT_EQ(ev.key(g, "n5", 0), before);

    // The same subgraph under other ids has the same key, so it shares cached values.
    Graph other = parse(R"({"cloudgraph": 1, "nodes": {
        "a": {"type": "TestSource", "params": {"value": 1}},
        "b": {"type": "TestAdd", "inputs": {"values": "a.values"}, "position": [40, 90]}}})");
    EXPECT_EQ(ev.key(other, "b", 0), ev.key(g, "n2", 0));  // a position is not cooked
    ev.pull(g, "n2", 0);
    resetCookCounts();
    ev.pull(other, "b", 0);
    EXPECT_EQ(totalCookCount(), 0u);
}

TEST_F(EvaluatorTest, FrameIndependentNodesCookOncePerAnimation)
{
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 9}, "nodes": {
        "src": {"type": "TestSource"},
        "add": {"type": "TestAdd", "inputs": {"values": "src.values"}},
        "pass": {"type": "TestFail", "inputs": {"values": "add.values"}}}})");
    Evaluator ev(registry, {});
    ev.cookFrames(g, 0, 9);
    EXPECT_EQ(cookCount("src"), 1u);
    EXPECT_EQ(cookCount("add"), 1u);
    EXPECT_EQ(cookCount("pass"), 10u);
    EXPECT_EQ(ev.key(g, "add", 0), ev.key(g, "add", 7));
    EXPECT_NE(ev.key(g, "pass", 0), ev.key(g, "pass", 7));
}

TEST_F(EvaluatorTest, SimulationCostsOneStepPerFrame)
{
    const int n = 40;
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 80}, "nodes": {
        "src": {"type": "TestSource", "params": {"value": 2, "count": 3}},
        "sim": {"type": "TestSim", "inputs": {"values": "src.values"}}}})");
    Evaluator ev(registry, {});
    ev.cookFrames(g, 0, n);
    EXPECT_EQ(cookCount("sim"), static_cast<std::size_t>(n + 1));  // start frame + n steps
    // state(f) = sum over k=0..f of (2 + k)
    const float expected = static_cast<float>(2 * (n + 1) + n * (n + 1) / 2);
    EXPECT_EQ(values(ev.pull(g, "sim", n), "state"), std::vector<float>(3, expected));
    EXPECT_EQ(cookCount("sim"), static_cast<std::size_t>(n + 1));

    // Extending the range resumes from the cached last frame.
    resetCookCounts();
    ev.cookFrames(g, 0, 2 * n);
    EXPECT_EQ(cookCount("sim"), static_cast<std::size_t>(n));

    // Pulling a late frame from a cold cache steps from the start frame, once per frame.
    Evaluator cold(registry, {});
    resetCookCounts();
    cold.pull(g, "sim", n);
    EXPECT_EQ(cookCount("sim"), static_cast<std::size_t>(n + 1));
    EXPECT_EQ(cookCount("src"), 1u);
}

TEST_F(EvaluatorTest, SimulationResumesFromTheDiskCacheAcrossEvaluators)
{
    test::TempDir dir;
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 20}, "nodes": {
        "src": {"type": "TestSource"},
        "sim": {"type": "TestSim", "inputs": {"values": "src.values"}}}})");
    EvaluatorOptions options;
    options.diskCache = std::make_shared<DiskCache>(dir.path());
    {
        Evaluator first(registry, options);
        first.cookFrames(g, 0, 10);
    }
    resetCookCounts();
    Evaluator second(registry, options);
    second.cookFrames(g, 15, 15);
    EXPECT_EQ(cookCount("sim"), 5u);  // frames 11..15, from the stored frame 10
    EXPECT_EQ(cookCount("src"), 0u);
}

TEST_F(EvaluatorTest, MemoryOnlyNodesNeverReachTheDiskCache)
{
    addTestAddCopy("TestAddMemoryOnly", false, true);
    test::TempDir dir;
    const Graph g = parse(R"({"cloudgraph": 1, "nodes": {
        "src": {"type": "TestSource"},
        "kept": {"type": "TestAdd", "inputs": {"values": "src.values"}},
        "regenerated": {"type": "TestAddMemoryOnly", "inputs": {"values": "kept.values"}}}})");
    EvaluatorOptions options;
    options.diskCache = std::make_shared<DiskCache>(dir.path());
    const auto first = values(Evaluator(registry, options).pull(g, "regenerated", 0), "values");
    resetCookCounts();
    Evaluator second(registry, options);
    EXPECT_EQ(values(second.pull(g, "regenerated", 0), "values"), first);
    EXPECT_EQ(cookCount("kept"), 0u);         // read back from disk
    EXPECT_EQ(cookCount("regenerated"), 1u);  // never stored there: cooked again
}

TEST_F(EvaluatorTest, UncachedNodesCookAgainAndTheirInputsStayCached)
{
    addTestAddCopy("TestAddTransient", true, false);
    const Graph g = parse(R"({"cloudgraph": 1, "nodes": {
        "src": {"type": "TestSource"},
        "kept": {"type": "TestAdd", "inputs": {"values": "src.values"}},
        "transient": {"type": "TestAddTransient", "inputs": {"values": "kept.values"}}}})");
    Evaluator ev(registry, {});
    const auto first = values(ev.pull(g, "transient", 0), "values");
    resetCookCounts();
    EXPECT_EQ(values(ev.pull(g, "transient", 0), "values"), first);
    EXPECT_EQ(cookCount("kept"), 0u);       // a memory hit
    EXPECT_EQ(cookCount("transient"), 1u);  // not kept: cooked again, the same values
}

TEST_F(EvaluatorTest, ACachedReaderSparesTheNeverStoredNodeItReads)
{
    addTestAddCopy("TestAddStream", false, false);  // as GenerateCloud: remade when read
    test::TempDir dir;
    const Graph g = parse(R"({"cloudgraph": 1, "nodes": {
        "src": {"type": "TestSource"},
        "stream": {"type": "TestAddStream", "inputs": {"values": "src.values"}},
        "reader": {"type": "TestAdd", "inputs": {"values": "stream.values"}}}})");
    EvaluatorOptions options;
    options.diskCache = std::make_shared<DiskCache>(dir.path());
    Evaluator first(registry, options);
    const auto cooked = values(first.pull(g, "reader", 0), "values");
    resetCookCounts();
    EXPECT_EQ(values(first.pull(g, "reader", 0), "values"), cooked);  // from memory
    EXPECT_EQ(cookCount("stream"), 0u);
    Evaluator second(registry, options);
    EXPECT_EQ(values(second.pull(g, "reader", 0), "values"), cooked);  // from disk
    EXPECT_EQ(cookCount("stream"), 0u);
    EXPECT_EQ(cookCount("src"), 0u);
    EXPECT_EQ(cookCount("reader"), 0u);
    ASSERT_EQ(second.report().records().size(), 1u);  // neither the stream nor its input
    EXPECT_EQ(second.report().records()[0].status, CookStatus::DiskHit);
}

TEST_F(EvaluatorTest, IntegrateMatchesItsClosedForm)
{
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 3, "end": 30}, "timeStep": 0.5,
        "nodes": {
        "rate": {"type": "TestSource", "params": {"value": 4, "count": 2}},
        "int": {"type": "Integrate", "params": {"initial": 1}, "inputs": {"rate": "rate.values"}}}})");
    Evaluator ev(registry, {});
    for (int f : {3, 4, 17, 30})  // state(f) = initial + (f - start) * dt * rate
        EXPECT_EQ(values(ev.pull(g, "int", f), "state"),
                  std::vector<float>(2, 1.0f + static_cast<float>(f - 3) * 0.5f * 4.0f));
}

TEST_F(EvaluatorTest, FailedCookCachesNothingAndNamesTheNode)
{
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 5}, "nodes": {
        "src": {"type": "TestSource"},
        "bad": {"type": "TestFail", "params": {"failAtFrame": 3}, "inputs": {"values": "src.values"}},
        "after": {"type": "TestAdd", "inputs": {"values": "bad.values"}}}})");
    Evaluator ev(registry, {});
    try {
        ev.cookFrames(g, 0, 5);
        FAIL() << "expected a CookError";
    } catch (const CookError& e) {
        EXPECT_EQ(e.nodeId(), "bad");
        EXPECT_FALSE(e.inputFault());
        EXPECT_NE(std::string(e.what()).find("frame 3"), std::string::npos);
    }
    EXPECT_EQ(cookCount("after"), 3u);  // frames 0..2 only
    EXPECT_EQ(ev.memoryCache().find(ev.key(g, "bad", 3)), nullptr);
    EXPECT_NE(ev.memoryCache().find(ev.key(g, "bad", 2)), nullptr);

    g.setParam("bad", "badInput", true);
    try {
        ev.cookFrames(g, 3, 3);
        FAIL() << "expected a CookError";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
    }
    g.setParam("bad", "failAtFrame", -1);
    EXPECT_NO_THROW(ev.cookFrames(g, 0, 5));
}

TEST_F(EvaluatorTest, InvalidArgumentFromACookIsBadInputNamingTheNode)
{
    // Algorithms and file readers refuse bad input with std::invalid_argument (a FormatError is
    // one); the evaluator reports it as a node's InputError would be, so nodes need no catch.
    addThrowingNode("TestInvalidArgument",
                    [](CookContext&) { throw std::invalid_argument("the map is empty"); });
    addThrowingNode("TestFormatError", [](CookContext&) {
        throw formats::FormatError("p.cgp:12", "not a primitive set");
    });
    addThrowingNode("TestInputError",
                    [](CookContext& ctx) { throw InputError(ctx.nodeId(), "the map is empty"); });
    const auto failure = [&](const std::string& type) {
        Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 2, "end": 2},
            "nodes": {"bad": {"type": ")" +
                        type + R"("}}})");
        Evaluator ev(registry, {});
        try {
            ev.cookFrames(g, 2, 2);
        } catch (const CookError& e) {
            EXPECT_EQ(e.nodeId(), "bad") << type;
            EXPECT_TRUE(e.inputFault()) << type;
            return std::string(e.what());
        }
        ADD_FAILURE() << type << " did not throw a CookError";
        return std::string();
    };
    const std::string asInputError = failure("TestInputError");
    EXPECT_EQ(asInputError, "test.json:/nodes/bad: node 'bad' frame 2: the map is empty");
    EXPECT_EQ(failure("TestInvalidArgument"), asInputError);
    EXPECT_EQ(failure("TestFormatError"),
              "test.json:/nodes/bad: node 'bad' frame 2: p.cgp:12: not a primitive set");
}

TEST_F(EvaluatorTest, CancellationThrowsAndCachesNothing)
{
    Graph g = parse(R"({"cloudgraph": 1, "nodes": {
        "src": {"type": "TestSource"},
        "wait": {"type": "TestWait", "inputs": {"values": "src.values"}}}})");
    EvaluatorOptions options;
    Evaluator ev(registry, options);
    std::thread canceller([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        ev.options().cancel->cancel();
    });
    EXPECT_THROW(ev.cookFrames(g, 0, 0), Cancelled);
    canceller.join();
    EXPECT_EQ(ev.memoryCache().find(ev.key(g, "wait", 0)), nullptr);
}

TEST_F(EvaluatorTest, ResultsAreIdenticalForOneAndTwoThreads)
{
    const char* text = R"({"cloudgraph": 1, "frames": {"start": 0, "end": 6}, "nodes": {
        "field": {"type": "RandomField", "params": {"width": 300, "height": 200, "seed": 7}},
        "osc": {"type": "Oscillator", "params": {"period": 5}},
        "scaled": {"type": "Scale", "inputs": {"values": "field.values", "factor": "osc.value"}},
        "other": {"type": "Scale", "params": {"factor": -2}, "inputs": {"values": "field.values"}},
        "sum": {"type": "Sum", "inputs": {"a": "scaled.values", "b": "other.values"}},
        "int": {"type": "Integrate", "inputs": {"rate": "sum.values"}}}})";
    std::vector<std::vector<float>> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        Graph g = parse(text);
        Evaluator ev(registry, {});
        results.push_back(values(ev.pull(g, "int", 6), "state"));
    }
    ASSERT_EQ(results[0].size(), 60000u);
    EXPECT_EQ(results[0], results[1]);
}

TEST_F(EvaluatorTest, ReportExplainsWhyEachNodeCooked)
{
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 9}, "nodes": {
        "src": {"type": "TestSource"},
        "sim": {"type": "TestSim", "inputs": {"values": "src.values"}}}})");
    Evaluator ev(registry, {});
    auto simReasons = [&] {
        std::vector<std::string> out;
        for (const CookRecord& r : ev.report().records())
            if (r.node == "sim" && r.status == CookStatus::Cooked) out.push_back(r.reason);
        ev.report().clear();
        return out;
    };
    ev.cookFrames(g, 0, 1);
    EXPECT_EQ(simReasons(), (std::vector<std::string>{"first cook", "first cook"}));
    ev.cookFrames(g, 0, 3);
    EXPECT_EQ(simReasons(), (std::vector<std::string>{"simulation step to frame 2",
                                                      "simulation step to frame 3"}));
    g.setParam("src", "value", 2.0);
    ev.cookFrames(g, 0, 0);
    EXPECT_EQ(simReasons(), (std::vector<std::string>{"input 'values' changed"}));
    for (const CookRecord& r : ev.report().records()) {
        if (r.node == "src") {
            EXPECT_EQ(r.reason, "parameter 'value' changed (1 -> 2)");
        }
    }
}

TEST_F(EvaluatorTest, ReportTotalsCountCooksAndHits)
{
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 2}, "nodes": {
        "src": {"type": "TestSource"},
        "sim": {"type": "TestSim", "inputs": {"values": "src.values"}}}})");
    Evaluator ev(registry, {});
    ev.cookFrames(g, 0, 2);
    const auto j = ev.report().toJson();
    EXPECT_EQ(j["totals"]["cooked"], 4);
    EXPECT_EQ(j["totals"]["memoryHits"], 2);  // src at frames 1 and 2
    EXPECT_EQ(j["records"].size(), 6u);
    EXPECT_EQ(j["nodes"]["sim"]["cooked"], 3);
}

TEST_F(EvaluatorTest, InputFilesEnterTheKeyByContentNotByPath)
{
    NodeDecl d;
    d.type = "TestReadText";
    d.category = "test";
    d.doc = "reads a text file";
    d.outputs = {port("text", "Text", "the file")};
    d.params = {inputFileParam("file", "", "the file")};
    d.hashExtra = [](const ParamSet& p, Hasher& h) { h.str(test::readFile(p.getString("file"))); };
    d.create = [] { return std::unique_ptr<Node>(); };
    registry.addNode(d);

    test::TempDir dir;
    test::writeFile(dir / "a.txt", "cumulus");
    test::writeFile(dir / "b.txt", "cumulus");
    test::writeFile(dir / "c.txt", "stratus");
    Graph g = parse(R"({"cloudgraph": 1, "nodes": {"read": {"type": "TestReadText"}}})");
    Evaluator ev(registry, {});
    g.setParam("read", "file", (dir / "a.txt").string());
    const Key a = ev.key(g, "read", 0);
    g.setParam("read", "file", (dir / "b.txt").string());
    EXPECT_EQ(ev.key(g, "read", 0), a);  // a copy elsewhere is the same value
    g.setParam("read", "file", (dir / "c.txt").string());
    EXPECT_NE(ev.key(g, "read", 0), a);

    NodeDecl unhashed = d;
    unhashed.type = "TestReadTextWithoutContentHash";
    unhashed.hashExtra = nullptr;
    EXPECT_THROW(registry.addNode(unhashed), std::invalid_argument);

    // A node that writes files cooks its frames in order: it cannot be of any order.
    NodeDecl unordered = d;
    unordered.type = "TestWriterOfAnyOrder";
    unordered.writesFiles = true;
    unordered.framesInAnyOrder = true;
    EXPECT_THROW(registry.addNode(unordered), std::invalid_argument);
}

TEST_F(EvaluatorTest, ReportShowsSmallOutputValues)
{
    Graph g = parse(R"({"cloudgraph": 1, "nodes": {
        "field": {"type": "TestSource", "params": {"value": 2, "count": 5}},
        "stats": {"type": "Statistics", "inputs": {"values": "field.values"}}}})");
    Evaluator ev(registry, {});
    ev.pull(g, "stats", 0);
    ev.pull(g, "stats", 0);  // a cache hit shows the values too
    const auto report = ev.report().toJson();
    for (const auto& r : report["records"]) {
        if (r["node"] != "stats") continue;
        EXPECT_EQ(r["values"]["count"], 5);
        EXPECT_EQ(r["values"]["mean"], 2.0);
        EXPECT_EQ(r["values"]["summary"], "frame 0: count 5 mean 2 min 2 max 2\n");
    }
}

TEST_F(EvaluatorTest, MemoryBudgetEvictsButResultsStayCorrect)
{
    Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 30}, "nodes": {
        "src": {"type": "TestSource", "params": {"count": 1000}},
        "sim": {"type": "TestSim", "inputs": {"values": "src.values"}}}})");
    EvaluatorOptions options;
    options.memoryBudgetBytes = 10000;  // about two frames of state
    Evaluator ev(registry, options);
    ev.cookFrames(g, 0, 30);
    EXPECT_LE(ev.memoryCache().bytes(), 10000u);
    resetCookCounts();
    // Frame 10 was evicted: it is recomputed by stepping from the start frame.
    const auto state = values(ev.pull(g, "sim", 10), "state");
    EXPECT_EQ(state[0], static_cast<float>(11 + 55));
    EXPECT_EQ(cookCount("sim"), 11u);
}

}  // namespace cg
