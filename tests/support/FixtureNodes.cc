#include "support/FixtureNodes.h"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CameraPath.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/VelocityVolume.h"

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

/// A lattice of particles that turn about the z axis at `spin` rad/s and rise at 2 m/s, as a
/// stream with motion (what GenerateCloud makes), in one chunk.
class SpinningLattice final : public CloudParticleStream {
public:
    SpinningLattice(std::vector<float> positions, double spin)
        : mPositions(std::move(positions)), mSpin(static_cast<float>(spin))
    {
        const std::size_t n = mPositions.size() / 3;
        for (std::size_t i = 0; i < n; ++i) {
            mVelocities.insert(mVelocities.end(),
                               {-mSpin * mPositions[3 * i + 1], mSpin * mPositions[3 * i], 2.0f});
            mIds.push_back(static_cast<std::uint32_t>(i));
        }
    }
    void forEachChunk(const std::function<void(const algo::CloudChunk&)>& consume,
                      CloudChunkFields fields, const std::function<void()>&) const override
    {
        const std::size_t n = mIds.size();
        const std::vector<std::uint8_t> levels(n, 1);
        const std::vector<std::uint32_t> sources(n, 0);
        algo::CloudChunk c;
        c.count = n;
        c.positions = mPositions.data();
        c.levels = fields.levels ? levels.data() : nullptr;
        c.sources = fields.sources ? sources.data() : nullptr;
        c.velocities = fields.velocities ? mVelocities.data() : nullptr;
        c.ids = fields.ids ? mIds.data() : nullptr;
        consume(c);
    }
    algo::CloudParticleArrays materialise(const std::function<void()>&) const override
    {
        const std::size_t n = mIds.size();
        return {algo::UninitArray<float>(mPositions),
                algo::UninitArray<std::uint8_t>(std::vector<std::uint8_t>(n, 1)),
                algo::UninitArray<std::uint32_t>(std::vector<std::uint32_t>(n, 0)),
                {}};
    }
    bool hasMotion() const override { return true; }

private:
    std::vector<float> mPositions, mVelocities;
    std::vector<std::uint32_t> mIds;
    float mSpin;
};

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
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] += in->values[i] + static_cast<float>(ctx.frame());
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
            if (ctx.params().getBool("badInput"))
                throw InputError(ctx.nodeId(), "bad input on purpose");
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

    // Cheap sources of the domain types, so the contract test never cooks a heavy simulation.
    NodeDecl primitive =
        decl("TestPrimitiveSource", "a small synthetic primitive set: a growing ball");
    primitive.outputs = {port("primitive", "PrimitiveSet", "the primitive set")};
    primitive.params = {intParam("frames", 8, "", "frames", 1, 1000),
                        floatParam("radius", 10.0, "m", "final radius", 0),
                        floatParam("sink", 0.0, "radii",
                                   "how far the ball hangs below its origin "
                                   "(0: it sits on it; 1: centred on it)",
                                   0, 2)};
    primitive.create = counted([](CookContext& ctx) {
        const auto frames = static_cast<int>(ctx.params().getInt("frames"));
        const double radius = ctx.params().getFloat("radius");
        const double lift = 1.0 - ctx.params().getFloat("sink");
        std::vector<std::uint32_t> counts;
        std::vector<float> positions;
        for (int s = 0; s < frames; ++s) {
            const std::uint32_t n = 8u * static_cast<std::uint32_t>(s + 1);
            counts.push_back(n);
            const double r = radius * (s + 1) / frames;
            for (std::uint32_t i = 0; i < n; ++i) {
                const double a = 2.399963 * i;  // golden-angle spiral on a sphere of radius r
                const double z = 1.0 - 2.0 * (i + 0.5) / n;
                const double rho = std::sqrt(1.0 - z * z);
                positions.insert(positions.end(), {static_cast<float>(r * rho * std::cos(a)),
                                                   static_cast<float>(r * rho * std::sin(a)),
                                                   static_cast<float>(r * z + lift * r)});
            }
        }
        ctx.setOutput("primitive", std::make_shared<PrimitiveSetData>(1.0, std::move(counts),
                                                                      std::move(positions)));
    });
    registry.addNode(primitive);

    NodeDecl cloud = decl("TestCloudSource",
                          "cloud particles on a lattice filling a ball, turning about z at "
                          "`spin` and rising at 2 m/s (a stream with motion)");
    cloud.outputs = {port("particles", "CloudParticles", "the particles")};
    cloud.params = {floatParam("radius", 20.0, "m", "ball radius", 1, 1000),
                    floatParam("spacing", 4.0, "m", "lattice spacing", 0.5, 100),
                    floatParam("spin", 0.01, "rad/s", "angular velocity about z", -1, 1)};
    cloud.create = counted([](CookContext& ctx) {
        const double r = ctx.params().getFloat("radius");
        const double h = ctx.params().getFloat("spacing");
        std::vector<float> positions;
        for (double x = -r; x <= r; x += h)
            for (double y = -r; y <= r; y += h)
                for (double z = -r; z <= r; z += h)
                    if (x * x + y * y + z * z <= r * r)
                        positions.insert(positions.end(),
                                         {static_cast<float>(x), static_cast<float>(y),
                                          static_cast<float>(z + r)});
        ctx.setOutput("particles",
                      std::make_shared<CloudParticlesData>(std::make_shared<SpinningLattice>(
                          std::move(positions), ctx.params().getFloat("spin"))));
    });
    registry.addNode(cloud);

    NodeDecl velocity = decl("TestVelocitySource",
                             "a velocity grid on TestFogSource's transform: a ball of voxels "
                             "all moving at `speed` m/s along x");
    velocity.outputs = {port("velocity", "VelocityVolume", "the velocity")};
    velocity.params = {floatParam("speed", 3.0, "m/s", "speed along x", -100, 100)};
    velocity.create = counted([](CookContext& ctx) {
        auto grid = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
        grid->setName("vel");
        const auto v = static_cast<float>(ctx.params().getFloat("speed"));
        grid->fill(openvdb::CoordBBox({-4, -4, -4}, {4, 4, 4}), openvdb::Vec3f(v, 0.0f, 0.0f));
        ctx.setOutput("velocity", std::make_shared<VelocityVolumeData>(grid));
    });
    registry.addNode(velocity);

    NodeDecl fog = decl("TestFogSource", "a fog volume: a ball of constant density");
    fog.outputs = {port("volume", "FogVolume", "the volume")};
    fog.params = {floatParam("radius", 8.0, "voxels", "ball radius", 1, 100),
                  floatParam("density", 1.0, "", "density inside", 0, 1)};
    fog.create = counted([](CookContext& ctx) {
        const double r = ctx.params().getFloat("radius");
        auto grid = openvdb::FloatGrid::create(0.0f);
        grid->setName("density");
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        auto acc = grid->getAccessor();
        const int n = static_cast<int>(std::ceil(r));
        for (int i = -n; i <= n; ++i)
            for (int j = -n; j <= n; ++j)
                for (int k = -n; k <= n; ++k)
                    if (i * i + j * j + k * k <= r * r)
                        acc.setValue({i, j, k},
                                     static_cast<float>(ctx.params().getFloat("density")));
        ctx.setOutput("volume", std::make_shared<FogVolumeData>(grid));
    });
    registry.addNode(fog);

    NodeDecl image = decl("TestImageSource", "a horizontal grey ramp");
    image.outputs = {port("image", "Image", "the image")};
    image.params = {intParam("width", 16, "px", "width", 1, 4096),
                    intParam("height", 8, "px", "height", 1, 4096)};
    image.create = counted([](CookContext& ctx) {
        const auto w = static_cast<int>(ctx.params().getInt("width"));
        const auto h = static_cast<int>(ctx.params().getInt("height"));
        std::vector<float> rgba;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float v = static_cast<float>(x) / static_cast<float>(w);
                rgba.insert(rgba.end(), {v, v, v, 1.0f});
            }
        ctx.setOutput("image", std::make_shared<ImageData>(w, h, std::move(rgba)));
    });
    registry.addNode(image);

    NodeDecl camera = decl("TestCameraSource", "a camera that dollies in over frames 0-10");
    camera.outputs = {port("camera", "CameraPath", "the camera path")};
    camera.params = {floatParam("fov", 40.0, "deg", "vertical field of view", 1, 170)};
    camera.create = counted([](CookContext& ctx) {
        algo::CameraKey a, b;
        a.position = {0.0, -4000.0, 800.0};
        a.lookAt = {0.0, 0.0, 1200.0};
        a.fovDegrees = ctx.params().getFloat("fov");
        b = a;
        b.frame = 10.0;
        b.position = {0.0, -3000.0, 900.0};
        ctx.setOutput("camera",
                      std::make_shared<CameraPathData>(std::vector<algo::CameraKey>{a, b}, 64, 48));
    });
    registry.addNode(camera);
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
        {"PrimitiveSet", {"TestPrimitiveSource", "primitive"}},
        {"CloudParticles", {"TestCloudSource", "particles"}},
        {"CloudSources", {"PrimitiveMapper", "sources"}},
        {"FogVolume", {"TestFogSource", "volume"}},
        {"Image", {"TestImageSource", "image"}},
        {"CameraPath", {"TestCameraSource", "camera"}},
        {"VelocityVolume", {"TestVelocitySource", "velocity"}},
    };
    auto it = sources.find(dataType);
    if (it == sources.end()) return "";
    outputPort = it->second.second;
    return it->second.first;
}

}  // namespace cg
