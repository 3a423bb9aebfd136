#include "support/FixtureNodes.h"

#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"

namespace cg {

namespace {

std::mutex gMutex;
std::map<std::string, std::size_t> gCounts;

void countCook(const CookContext& ctx)
{
    std::lock_guard<std::mutex> lock(gMutex);
    ++gCounts[ctx.nodeId()];
}

/// Wraps a lambda as a Node that counts its cooks.
template <class F>
std::function<std::unique_ptr<Node>()> counted(F body)
{
    struct Impl final : Node {
        explicit Impl(F f) : fn(std::move(f)) {}
        void cook(CookContext& ctx) override
        {
            countCook(ctx);
            fn(ctx);
        }
        F fn;
    };
    return [body] { return std::make_unique<Impl>(body); };
}

NodeDecl decl(const std::string& type, const std::string& doc)
{
    NodeDecl d;
    d.type = type;
    d.category = "test";
    d.doc = doc;
    return d;
}

}  // namespace

void registerFixtureNodes(Registry& registry)
{
    NodeDecl source = decl("TestSource", "count copies of value");
    source.outputs = {port("values", "FloatArray", "the values")};
    source.params = {floatParam("value", 1.0, "", "each element"),
                     intParam("count", 4, "", "how many", 0, 1 << 20)};
    source.create = counted([](CookContext& ctx) {
        ctx.setOutput("values", std::make_shared<FloatArrayData>(std::vector<float>(
                                    static_cast<std::size_t>(ctx.params().getInt("count")),
                                    static_cast<float>(ctx.params().getFloat("value")))));
    });
    registry.addNode(source);

    NodeDecl add = decl("TestAdd", "values + add");
    add.inputs = {port("values", "FloatArray", "input")};
    add.outputs = {port("values", "FloatArray", "input + add")};
    add.params = {floatParam("add", 1.0, "", "added to each element")};
    add.create = counted([](CookContext& ctx) {
        auto in = ctx.input<FloatArrayData>("values");
        std::vector<float> v(in->values);
        for (float& x : v) x += static_cast<float>(ctx.params().getFloat("add"));
        ctx.setOutput("values", std::make_shared<FloatArrayData>(std::move(v)));
    });
    registry.addNode(add);

    NodeDecl sim = decl("TestSim", "state = previous + values + frame");
    sim.simulation = true;
    sim.inputs = {port("values", "FloatArray", "added each step")};
    sim.outputs = {port("state", "FloatArray", "the state")};
    sim.create = counted([](CookContext& ctx) {
        auto in = ctx.input<FloatArrayData>("values");
        auto prev = ctx.previous<FloatArrayData>("state");
        std::vector<float> v = prev ? prev->values : std::vector<float>(in->values.size(), 0.0f);
        for (std::size_t i = 0; i < v.size(); ++i) v[i] += in->values[i] + static_cast<float>(ctx.frame());
        ctx.setOutput("state", std::make_shared<FloatArrayData>(std::move(v)));
    });
    registry.addNode(sim);

    NodeDecl fail = decl("TestFail", "passes values through, but fails at one frame");
    fail.frameDependent = true;
    fail.inputs = {port("values", "FloatArray", "input")};
    fail.outputs = {port("values", "FloatArray", "the input")};
    fail.params = {intParam("failAtFrame", -1, "", "frame at which to throw; -1 never", -1),
                   boolParam("badInput", false, "throw an InputError instead of a runtime_error")};
    fail.create = counted([](CookContext& ctx) {
        if (ctx.frame() == ctx.params().getInt("failAtFrame")) {
            if (ctx.params().getBool("badInput")) throw InputError(ctx.nodeId(), "bad input on purpose");
            throw std::runtime_error("failure on purpose");
        }
        ctx.setOutput("values", ctx.input<FloatArrayData>("values"));
    });
    registry.addNode(fail);

    NodeDecl wait = decl("TestWait", "spins until cancelled (or a bound), checking cancellation");
    wait.inputs = {port("values", "FloatArray", "input")};
    wait.outputs = {port("values", "FloatArray", "the input")};
    wait.params = {intParam("maxMilliseconds", 10000, "ms", "give up after this long", 0)};
    wait.create = counted([](CookContext& ctx) {
        for (std::int64_t i = 0; i < ctx.params().getInt("maxMilliseconds"); ++i) {
            ctx.checkCancelled();
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        ctx.setOutput("values", ctx.input<FloatArrayData>("values"));
    });
    registry.addNode(wait);

    NodeDecl intSource = decl("TestIntSource", "an Int");
    intSource.outputs = {port("value", "Int", "the value")};
    intSource.params = {intParam("value", 3, "", "the value")};
    intSource.create = counted([](CookContext& ctx) {
        ctx.setOutput("value", std::make_shared<IntData>(ctx.params().getInt("value")));
    });
    registry.addNode(intSource);

    NodeDecl textSource = decl("TestTextSource", "a Text");
    textSource.outputs = {port("value", "Text", "the value")};
    textSource.params = {stringParam("value", "hello", "the text")};
    textSource.create = counted([](CookContext& ctx) {
        ctx.setOutput("value", std::make_shared<TextData>(ctx.params().getString("value")));
    });
    registry.addNode(textSource);
}

std::size_t cookCount(const std::string& nodeId)
{
    std::lock_guard<std::mutex> lock(gMutex);
    auto it = gCounts.find(nodeId);
    return it == gCounts.end() ? 0 : it->second;
}

std::size_t totalCookCount()
{
    std::lock_guard<std::mutex> lock(gMutex);
    std::size_t n = 0;
    for (const auto& [id, c] : gCounts) n += c;
    return n;
}

void resetCookCounts()
{
    std::lock_guard<std::mutex> lock(gMutex);
    gCounts.clear();
}

std::string sourceNodeFor(const std::string& dataType, std::string& outputPort)
{
    static const std::map<std::string, std::pair<std::string, std::string>> sources = {
        {"Float", {"Constant", "value"}},
        {"Int", {"TestIntSource", "value"}},
        {"FloatArray", {"TestSource", "values"}},
        {"Text", {"TestTextSource", "value"}},
        {"Map2D", {"NoiseMap", "map"}},
        {"Atmosphere", {"Atmosphere", "atmosphere"}},
        {"VapourParticles", {"VapourEmitter", "particles"}},
        {"Condensation", {"Condensation", "condensation"}},
    };
    auto it = sources.find(dataType);
    if (it == sources.end()) return "";
    outputPort = it->second.second;
    return it->second.first;
}

}  // namespace cg
