// Issue 14's real atmosphere through the engine: a sounding's lifting condensation level and
// equilibrium level, wind, shear, anvils and irregular bases, each against a closed form or a
// value computed here from the sounding's own numbers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "algo/atmosphere/Convective.h"
#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Thermodynamics.h"
#include "algo/atmosphere/VapourEmission.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "formats/Sounding.h"
#include "nodes/Builtin.h"
#include "nodes/atmosphere/SoundingProfile.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

using nlohmann::json;

const std::string kDeepConvection =
    (std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "graphs" / "soundings" / "deep_convection.csv")
        .string();

/// Emission, rise and condensation; `atmosphere`, `emit` and `rise` parameters as given. An
/// 8 x 8 map: with equal min and max the emission is uniform whatever the noise.
json pipeline(int frames, double timeStep, const json& atmosphere, const json& emit,
              const json& rise, const json& noise = json::object())
{
    json n = {{"width", 8}, {"height", 8}, {"seed", 3}};
    n.update(noise);
    return {
        {"cloudgraph", 1},
        {"frames", {{"start", 0}, {"end", frames}}},
        {"timeStep", timeStep},
        {"nodes",
         {{"noise", {{"type", "NoiseMap"}, {"params", n}}},
          {"moisture",
           {{"type", "NoiseMap"}, {"params", {{"width", 8}, {"height", 8}, {"seed", 11}}}}},
          {"atmosphere", {{"type", "Atmosphere"}, {"params", atmosphere}}},
          {"emit",
           {{"type", "VapourEmitter"},
            {"inputs",
             {{"map", "noise.map"},
              {"moisture", "moisture.map"},
              {"atmosphere", "atmosphere.atmosphere"}}},
            {"params", emit}}},
          {"rise",
           {{"type", "ThermalIntegrator"},
            {"inputs", {{"particles", "emit.particles"}, {"atmosphere", "atmosphere.atmosphere"}}},
            {"params", rise}}},
          {"condense",
           {{"type", "Condensation"},
            {"inputs",
             {{"particles", "rise.particles"}, {"atmosphere", "atmosphere.atmosphere"}}}}}}}};
}

json uniformEmission(double temperature)
{
    return {{"minParticlesPerCell", 1},
            {"maxParticlesPerCell", 1},
            {"minHeight", 0},
            {"maxHeight", 0},
            {"minTemperature", temperature},
            {"maxTemperature", temperature}};
}

json soundingAtmosphere()
{
    return {{"profile", "sounding"}, {"soundingFile", kDeepConvection}, {"dryLapseRate", 9.76}};
}

class RealAtmosphere : public ::testing::Test {
protected:
    void SetUp() override { registerBuiltinNodes(registry); }

    /// Runs frames 0..last, calling `each` with the condensation state of every frame.
    void run(const json& graph, const std::function<void(int, const CondensationData&)>& each)
    {
        const Graph g = parseGraph(graph.dump(), "real_atmosphere.json", registry);
        Evaluator ev(registry, {});
        const int last = graph["frames"]["end"];
        ev.cookFrames(g, 0, last, {"condense"}, [&](int frame, const Evaluator::FrameOutputs& out) {
            each(frame, *std::dynamic_pointer_cast<const CondensationData>(
                            out[g.indexOf("condense")]->at("condensation")));
        });
    }

    /// Each particle's height in the frame it condensed (NaN: never).
    std::vector<float> baseHeights(const json& graph)
    {
        std::vector<float> base;
        run(graph, [&](int frame, const CondensationData& c) {
            base.resize(c.particles->size(), std::nanf(""));
            for (std::size_t i = 0; i < base.size(); ++i)
                if (c.condensedFrame[i] == frame) base[i] = c.particles->z[i];
        });
        return base;
    }

    Registry registry;
};

/// A convective afternoon the project ships nowhere (ours, made up): a mixed layer dry
/// adiabatic from 31 C at 200 m to 1.7 km, dew point 19 C at the ground; pressures left to
/// the hydrostatic fill.
const char* kUnseenSounding =
    "height_m,temperature_C,dewpoint_C,pressure_hPa,wind_dir_deg,wind_speed_ms\n"
    "200,31.0,19.0,,230,2.0\n700,26.1,18.1,,235,3.0\n1200,21.2,17.2,,240,4.0\n"
    "1700,16.3,14.0,,245,5.0\n2500,11.1,5.0,,250,6.0\n3500,4.6,-5.0,,255,7.0\n"
    "5500,-8.4,-20.0,,260,9.0\n9000,-31.0,-40.0,,265,14.0\n12000,-55.0,-65.0,,270,18.0\n";

algo::EnvironmentProfile deepConvection()
{
    return profileFromSounding(formats::readSounding(kDeepConvection));
}

double standardDeviation(const std::vector<float>& v)
{
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    double sum = 0.0;
    for (float x : v) sum += (x - mean) * (x - mean);
    return std::sqrt(sum / static_cast<double>(v.size()));
}

}  // namespace

TEST_F(RealAtmosphere, UniformEmissionCondensesAtTheSoundingsLiftingCondensationLevel)
{
    // Independently of the code: a parcel starting at T0 with the sounding's surface dew point
    // (22 C, its first row) cools 9.76 C/km while its dew point falls 1.8 C/km.
    const double t0 = 31.0, surfaceDewpoint = 22.0;
    const double lcl = (t0 - surfaceDewpoint) / (9.76e-3 - 1.8e-3);  // 1131 m above the ground
    const double timeStep = 2.0;
    float fastest = 0.0f;
    std::vector<float> base;
    run(pipeline(300, timeStep, soundingAtmosphere(), uniformEmission(t0),
                 {{"buoyancy", "parcel"}}),
        [&](int frame, const CondensationData& c) {
            base.resize(c.particles->size(), std::nanf(""));
            for (std::size_t i = 0; i < base.size(); ++i) {
                if (c.condensedFrame[i] == frame) base[i] = c.particles->z[i];
                fastest = std::max(fastest, c.particles->vz[i]);
            }
        });
    ASSERT_EQ(base.size(), 64u);
    const double tolerance = std::max(0.05 * lcl, fastest * timeStep);
    for (float z : base) {
        ASSERT_FALSE(std::isnan(z)) << "a particle never condensed";
        EXPECT_NEAR(z, lcl, tolerance);
    }
}

TEST_F(RealAtmosphere, TowersStopAtTheEquilibriumLevel)
{
    const algo::EnvironmentProfile profile = deepConvection();
    const double el =
        algo::liftParcel(profile, profile.groundHeight()).elM - profile.groundHeight();
    ASSERT_NEAR(el, 11800.0, 300.0);  // the shipped sounding's, as docs/atmosphere.md says
    float highest = 0.0f;
    std::vector<float> last;
    run(pipeline(500, 5.0, soundingAtmosphere(), uniformEmission(31.0),
                 {{"buoyancy", "parcel"}, {"drag", 1e-3}}),
        [&](int, const CondensationData& c) {
            highest =
                std::max(highest, *std::max_element(c.particles->z.begin(), c.particles->z.end()));
            last = c.particles->z;
        });
    EXPECT_LE(highest, 1.10 * el) << "the overshoot goes too far";
    const double mean =
        std::accumulate(last.begin(), last.end(), 0.0) / static_cast<double>(last.size());
    EXPECT_NEAR(mean, el, 0.10 * el) << "the tops did not settle at the equilibrium level";
}

/// Twice the root-mean-square horizontal distance of the particles from their centroid.
double width(const VapourParticlesData& p, const std::vector<std::size_t>& which)
{
    double x = 0.0, y = 0.0;
    for (std::size_t i : which) x += p.xs()[i], y += p.ys()[i];
    x /= static_cast<double>(which.size());
    y /= static_cast<double>(which.size());
    double r2 = 0.0;
    for (std::size_t i : which)
        r2 += (p.xs()[i] - x) * (p.xs()[i] - x) + (p.ys()[i] - y) * (p.ys()[i] - y);
    return 2.0 * std::sqrt(r2 / static_cast<double>(which.size()));
}

TEST_F(RealAtmosphere, OutflowSpreadsTheTopIntoAnAnvil)
{
    const algo::EnvironmentProfile profile = deepConvection();
    const double el =
        algo::liftParcel(profile, profile.groundHeight()).elM - profile.groundHeight();
    // One tower: a centre-weighted 2 km map emits only near its middle.
    json emit = uniformEmission(31.0);
    emit["minParticlesPerCell"] = 0;
    emit["maxParticlesPerCell"] = 4;
    const json noise = {{"width", 20},
                        {"height", 20},
                        {"cellSize", 100.0},
                        {"centreBias", 1.0},
                        {"centreRadius", 0.3}};
    double midWidth = 0.0, topWidth = 0.0;
    std::size_t atTop = 0, total = 0;
    run(pipeline(600, 5.0, soundingAtmosphere(), emit,
                 {{"buoyancy", "parcel"}, {"drag", 1e-3}, {"outflowDivergence", 2e-3}}, noise),
        [&](int frame, const CondensationData& c) {
            const VapourParticlesData& p = *c.particles;
            total = p.size();
            std::vector<std::size_t> all(p.size());
            std::iota(all.begin(), all.end(), 0);
            const double mean =
                std::accumulate(p.z.begin(), p.z.end(), 0.0) / static_cast<double>(p.size());
            if (midWidth == 0.0 && mean >= 0.5 * el)
                midWidth = width(p, all);  // the tower passing mid-height
            if (frame == 600) {
                std::vector<std::size_t> top;
                for (std::size_t i = 0; i < p.size(); ++i)
                    if (p.z[i] >= 0.8 * el) top.push_back(i);
                atTop = top.size();
                topWidth = width(p, top);
            }
        });
    ASSERT_GT(total, 50u);
    ASSERT_GT(midWidth, 0.0) << "the tower never reached mid-height";
    EXPECT_GT(atTop, total / 2) << "most of the tower should have reached the top";
    EXPECT_GE(topWidth, 2.0 * midWidth) << "mid " << midWidth << " m, top " << topWidth << " m";
}

TEST_F(RealAtmosphere, TheOutflowMovesNoParticleFasterThanItsCap)
{
    json emit = uniformEmission(31.0);
    emit["maxParticlesPerCell"] = 4;
    const json noise = {{"width", 20}, {"height", 20}, {"cellSize", 100.0}};
    const auto fastest = [&](double cap) {
        double top = 0.0;
        run(pipeline(300, 5.0, soundingAtmosphere(), emit,
                     {{"buoyancy", "parcel"},
                      {"drag", 1e-3},
                      {"outflowDivergence", 2e-3},
                      {"outflowMaxSpeed", cap}},
                     noise),
            [&](int, const CondensationData& c) {
                const VapourParticlesData& p = *c.particles;
                for (std::size_t i = 0; i < p.vxs().size(); ++i)  // calm air: outflow alone
                    top = std::max(top, std::hypot(double(p.vxs()[i]), double(p.vys()[i])));
            });
        return top;
    };
    const double uncapped = fastest(0.0);
    ASSERT_GT(uncapped, 3.0) << "the outflow never ran faster than the cap to test";
    EXPECT_LE(fastest(3.0), 3.0 + 1e-4);
}

TEST_F(RealAtmosphere, ConstantWindMovesEveryParticleByUTAndNothingElse)
{
    const int frames = 100;
    const double timeStep = 0.5, speed = 12.0;
    json windy = {{"wind", "layers"},
                  {"windHeights", {0.0}},
                  {"windSpeeds", {speed}},
                  {"windDirections", {270.0}}};
    std::shared_ptr<const VapourParticlesData> calm, blown;
    run(pipeline(frames, timeStep, json::object(), json::object(), json::object()),
        [&](int, const CondensationData& c) { calm = c.particles; });
    run(pipeline(frames, timeStep, windy, json::object(), json::object()),
        [&](int, const CondensationData& c) { blown = c.particles; });
    ASSERT_EQ(calm->size(), blown->size());
    EXPECT_FALSE(calm->movedHorizontally());
    ASSERT_TRUE(blown->movedHorizontally());
    EXPECT_EQ(blown->z, calm->z);  // the wind leaves the paper's vertical motion bit for bit
    EXPECT_EQ(blown->temperature, calm->temperature);
    const double ut = speed * timeStep * frames;  // from the west: toward +x
    for (std::size_t i = 0; i < blown->size(); ++i) {
        const float x0 = blown->statics->x[i];
        // Float sums of u dt, one rounding per step.
        const float x = blown->xs()[i];
        const double ulps = frames * (static_cast<double>(std::nextafter(x, 1e9f)) - x);
        ASSERT_NEAR(blown->xs()[i] - x0, ut, ulps) << "particle " << i;
        ASSERT_EQ(blown->ys()[i], blown->statics->y[i]) << "particle " << i;
    }
}

TEST_F(RealAtmosphere, LinearShearTiltsTheTowerByTheExpectedAngle)
{
    // Constant acceleration (the environment cools at the particles' own 10 C/km, nothing
    // condenses, no gravity): z = a t^2 / 2 for every particle, so under u = s z each one is
    // at x - x0 = s a t^3 / 6 = (s t / 3) z: the tower leans by atan(s t / 3) at time t.
    const int frames = 400;
    const double timeStep = 0.5, shear = 4e-3;  // 1/s: 40 m/s over 10 km
    const json atmosphere = {{"environmentLapseRate", 10.0},
                             {"dewPoint", -60.0},
                             {"gravity", 0.0},
                             {"wind", "layers"},
                             {"windHeights", {0.0, 20000.0}},
                             {"windSpeeds", {0.0, shear * 20000.0}},
                             {"windDirections", {270.0, 270.0}}};
    std::shared_ptr<const VapourParticlesData> p;
    run(pipeline(frames, timeStep, atmosphere, {{"minTemperature", 25.0}, {"maxTemperature", 30.0}},
                 {{"buoyancyCoefficient", 0.05}}),  // a = 0.25 .. 0.5 m/s^2: 5 to 10 km
        [&](int, const CondensationData& c) { p = c.particles; });
    double zz = 0.0, xz = 0.0;
    for (std::size_t i = 0; i < p->size(); ++i) {
        const double z = p->z[i] - p->statics->startZ[i];
        zz += z * z;
        xz += (p->xs()[i] - p->statics->x[i]) * z;
    }
    ASSERT_GT(zz, 0.0);
    const double t = frames * timeStep;
    const double expected = std::atan(shear * t / 3.0), measured = std::atan(xz / zz);
    EXPECT_GT(expected, 0.25);  // a visible lean, not a rounding
    EXPECT_LT(*std::max_element(p->z.begin(), p->z.end()), 20000.0f);  // all inside the shear
    EXPECT_NEAR(measured, expected, 0.2 * expected);
}

TEST_F(RealAtmosphere, StormFrameSubtractsTheMeanWindBelowItsSteeringDepth)
{
    // Under u = s z the 0-6 km mean wind is s 3000 m: in the storm's frame every particle ends
    // s 3000 t further west than in the ground's, at the same height, whatever its path.
    const int frames = 200;
    const double timeStep = 0.5, shear = 4e-3;
    json atmosphere = {{"environmentLapseRate", 10.0},
                       {"dewPoint", -60.0},
                       {"gravity", 0.0},
                       {"wind", "layers"},
                       {"windHeights", {0.0, 20000.0}},
                       {"windSpeeds", {0.0, shear * 20000.0}},
                       {"windDirections", {270.0, 270.0}}};
    const json emitter = {{"minTemperature", 25.0}, {"maxTemperature", 30.0}};
    const json thermal = {{"buoyancyCoefficient", 0.05}};
    std::shared_ptr<const VapourParticlesData> ground, storm;
    run(pipeline(frames, timeStep, atmosphere, emitter, thermal),
        [&](int, const CondensationData& c) { ground = c.particles; });
    atmosphere["windFrame"] = "storm";
    run(pipeline(frames, timeStep, atmosphere, emitter, thermal),
        [&](int, const CondensationData& c) { storm = c.particles; });
    ASSERT_EQ(ground->size(), storm->size());
    EXPECT_EQ(storm->z, ground->z);
    const auto expectShift = [&](const VapourParticlesData& moved, double shift) {
        for (std::size_t i = 0; i < moved.size(); ++i) {
            const float x = ground->xs()[i];
            const double ulps = 2.0 * frames * (static_cast<double>(std::nextafter(x, 1e9f)) - x);
            ASSERT_NEAR(moved.xs()[i] - x, -shift, ulps) << "particle " << i;
            ASSERT_EQ(moved.ys()[i], ground->ys()[i]) << "particle " << i;
        }
    };
    expectShift(*storm, shear * 3000.0 * frames * timeStep);  // 240 m
    // A cumulus field's frame: the 0-2.5 km mean, s 1250 m.
    atmosphere["steeringDepth"] = 2500.0;
    run(pipeline(frames, timeStep, atmosphere, emitter, thermal),
        [&](int, const CondensationData& c) { storm = c.particles; });
    expectShift(*storm, shear * 1250.0 * frames * timeStep);
}

TEST_F(RealAtmosphere, EmissionDurationReleasesEachParticleAtItsOwnTime)
{
    // A particle released at r seconds is first stepped from the frame at or after r, so its
    // velocity first changes in the frame after: frame ceil(r / dt) + 1.
    const double duration = 60.0, timeStep = 1.0;
    json emit = uniformEmission(30.0);
    emit["emissionDuration"] = duration;
    std::vector<int> firstMoved;
    run(pipeline(80, timeStep, json::object(), emit, json::object()),
        [&](int frame, const CondensationData& c) {
            firstMoved.resize(c.particles->size(), -1);
            for (std::size_t i = 0; i < firstMoved.size(); ++i)
                if (firstMoved[i] < 0 && c.particles->vz[i] != 0.0f) firstMoved[i] = frame;
        });
    ASSERT_EQ(firstMoved.size(), 64u);
    std::vector<int> distinct;
    for (std::size_t i = 0; i < firstMoved.size(); ++i) {
        const float release = algo::releaseTime(0, static_cast<std::uint32_t>(i), duration);
        ASSERT_GE(release, 0.0f);
        ASSERT_LT(release, duration);
        EXPECT_EQ(firstMoved[i], static_cast<int>(std::ceil(release / timeStep)) + 1) << i;
        distinct.push_back(firstMoved[i]);
    }
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    EXPECT_GT(distinct.size(), 30u);  // spread over the minute, not released together
}

TEST_F(RealAtmosphere, IrregularBasesSpreadWithTheMoistureAmplitude)
{
    // The paper's atmosphere and a uniform emission: every particle condenses at
    // (30 - 16) / 10 C/km = 1400 m. A dew-point offset d moves its base by -d / 10 C/km.
    std::vector<double> spread;
    for (double amplitude : {0.0, 1.0, 2.0}) {
        const std::vector<float> base = baseHeights(pipeline(
            120, 0.2, json::object(),
            [&] {
                json e = uniformEmission(30.0);
                e["moistureAmplitude"] = amplitude;
                return e;
            }(),
            json::object()));
        ASSERT_TRUE(std::none_of(base.begin(), base.end(), [](float z) { return std::isnan(z); }));
        spread.push_back(standardDeviation(base));
    }
    EXPECT_EQ(spread[0], 0.0);
    EXPECT_GT(spread[1], 10.0);
    EXPECT_NEAR(spread[2] / spread[1], 2.0, 0.2);
}

TEST_F(RealAtmosphere, ASoundingIsFoundBesideItsGraphAndKeyedByItsContent)
{
    namespace fs = std::filesystem;
    test::TempDir dir;
    fs::create_directories(dir / "soundings");
    fs::copy_file(kDeepConvection, dir / "soundings" / "day.csv");
    fs::copy_file(kDeepConvection, dir / "soundings" / "copy.csv");
    auto graphWith = [&](const std::string& file) {
        const json g = {{"cloudgraph", 1},
                        {"frames", {{"start", 0}, {"end", 0}}},
                        {"nodes",
                         {{"atmosphere",
                           {{"type", "Atmosphere"},
                            {"params", {{"profile", "sounding"}, {"soundingFile", file}}}}}}}};
        std::ofstream(dir / "g.json") << g.dump();
        return loadGraph(dir / "g.json", registry);  // the working directory is elsewhere
    };
    const Graph g = graphWith("soundings/day.csv");
    Evaluator ev(registry, {});
    const auto a = std::dynamic_pointer_cast<const AtmosphereData>(
        ev.pull(g, "atmosphere", 0)->at("atmosphere"));
    ASSERT_TRUE(a && a->atmosphere.profile);
    EXPECT_EQ(a->atmosphere.profile->groundHeight(), 200.0);

    // The key is the file's content: another name with the same bytes is the same key; one
    // changed value is not.
    const Key key = ev.key(g, "atmosphere", 0);
    EXPECT_EQ(ev.key(graphWith("soundings/copy.csv"), "atmosphere", 0), key);
    std::ofstream(dir / "soundings" / "copy.csv", std::ios::app) << "17000,-42.0,,,,\n";
    EXPECT_NE(ev.key(graphWith("soundings/copy.csv"), "atmosphere", 0), key);
}

TEST_F(RealAtmosphere, WeatherReportWritesTheCloudAndTheParcel)
{
    test::TempDir out;
    json emit = uniformEmission(31.0);
    emit["emissionDuration"] = 400.0;  // air keeps arriving, so the base is where it condenses
    json graph = pipeline(300, 2.0, soundingAtmosphere(), emit, {{"buoyancy", "parcel"}});
    graph["nodes"]["report"] = {
        {"type", "WriteWeatherReport"},
        {"inputs",
         {{"condensation", "condense.condensation"}, {"atmosphere", "atmosphere.atmosphere"}}},
        {"params", {{"file", "weather.####"}, {"every", 300}}}};
    const Graph g = parseGraph(graph.dump(), "report.json", registry);
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 0, 300, {"report"});
    for (const char* ext : {".json", ".csv", ".png"})
        EXPECT_TRUE(std::filesystem::exists(out / (std::string("weather.0300") + ext))) << ext;
    EXPECT_FALSE(std::filesystem::exists(out / "weather.0001.json"));

    const json report = json::parse(std::ifstream(out / "weather.0300.json"));
    // The sounding's own levels (cloudgraph sounding prints them), and the uniform emission's
    // base at its particles' LCL, 1131 m above the 200 m ground.
    EXPECT_NEAR(report["lcl_m"].get<double>(), 1205.0, 1.0);
    EXPECT_NEAR(report["el_m"].get<double>(), 11984.0, 1.0);
    EXPECT_NEAR(report["cloud_base_m"].get<double>(), 200.0 + 1131.0, 0.05 * 1131.0);
    const int condensed = report["condensed_particles"].get<int>();
    EXPECT_GT(condensed, 0);
    EXPECT_LT(condensed, 64);  // the last ones released are still rising to their LCL
    EXPECT_GT(report["cloud_top_m"].get<double>(), report["cloud_base_m"].get<double>());
    EXPECT_GT(report["parcel"].size(), 100u);
    const algo::ConvectiveLevels levels = algo::convectiveLevels(deepConvection());
    EXPECT_NEAR(report["ccl_m"].get<double>(), levels.cclM, 1e-3 * levels.cclM);
    EXPECT_NEAR(report["convective_temperature_c"].get<double>(), levels.convectiveTemperatureC,
                1e-3);
    EXPECT_EQ(report["warning"], "");  // the deep-convection day's surface air rises freely
    double cloudy = 0.0;
    for (const auto& f : report["cloud_fraction"]["from_ground"])
        cloudy = std::max(cloudy, f.get<double>());
    EXPECT_GT(cloudy, 0.0);
    EXPECT_LE(cloudy, 1.0);

    std::ifstream csv(out / "weather.0300.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header, "height_m,pressure_hPa,environment_C,dewpoint_C,parcel_C,cloud_fraction");
}

TEST_F(RealAtmosphere, AConvectiveStartCondensesAnUnseenSoundingAtEachParticlesLcl)
{
    test::TempDir dir;
    test::writeFile(dir / "unseen.csv", kUnseenSounding);
    const json atmosphere = {{"profile", "sounding"},
                             {"soundingFile", (dir / "unseen.csv").string()},
                             {"dryLapseRate", 9.76}};
    json emit = {{"minParticlesPerCell", 1},
                 {"maxParticlesPerCell", 1},
                 {"minHeight", 0},
                 {"maxHeight", 300}};
    // The shipped fair-weather graph's Eq. 5 temperatures (22.3-24.8 C) start colder than
    // this afternoon's 31 C air: nothing rises to condense.
    json paper = emit;
    paper["minTemperature"] = 22.3;
    paper["maxTemperature"] = 24.8;
    std::size_t paperCondensed = 0;
    run(pipeline(150, 4.0, atmosphere, paper, {{"buoyancy", "parcel"}}),
        [&](int, const CondensationData& c) {
            paperCondensed = static_cast<std::size_t>(
                std::count_if(c.condensedFrame.begin(), c.condensedFrame.end(),
                              [](std::int32_t f) { return f >= 0; }));
        });
    EXPECT_EQ(paperCondensed, 0u);

    emit["start"] = "convective";
    emit["temperatureExcess"] = 0.5;
    std::vector<float> base, lcl;
    run(pipeline(150, 4.0, atmosphere, emit, {{"buoyancy", "parcel"}}),
        [&](int frame, const CondensationData& c) {
            const VapourStatics& st = *c.particles->statics;
            base.resize(c.particles->size(), std::nanf(""));
            if (frame == 0) {
                // Each particle's own LCL from its start: 125 m per C of depression.
                const auto profile =
                    profileFromSounding(formats::readSounding((dir / "unseen.csv").string()));
                for (std::size_t i = 0; i < st.size(); ++i) {
                    const double td = profile.dewpoint(profile.groundHeight() + st.startZ[i]) +
                                      st.dewpointOffset[i];
                    lcl.push_back(static_cast<float>(st.startZ[i] +
                                                     (c.particles->temperature[i] - td) / 7.96e-3));
                }
            }
            for (std::size_t i = 0; i < base.size(); ++i)
                if (c.condensedFrame[i] == frame) base[i] = c.particles->z[i];
        });
    ASSERT_EQ(base.size(), lcl.size());
    std::vector<double> errors;
    for (std::size_t i = 0; i < base.size(); ++i)
        if (!std::isnan(base[i])) errors.push_back(std::abs(base[i] - lcl[i]) / lcl[i]);
    EXPECT_GE(errors.size(), 95 * base.size() / 100) << "particles that never condensed";
    ASSERT_FALSE(errors.empty());
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    EXPECT_LT(errors[errors.size() / 2], 0.08);
    // Their bases sit near the convective condensation level (about 1.5 km up).
    const auto profile = profileFromSounding(formats::readSounding((dir / "unseen.csv").string()));
    const double ccl = algo::convectiveLevels(profile).cclM - profile.groundHeight();
    EXPECT_NEAR(lcl[0], ccl + 0.5 / 7.96e-3, 80.0);
}

TEST_F(RealAtmosphere, AnExcessStartsEachParticleAboveTheAirAtItsStartHeight)
{
    json emit = {{"minParticlesPerCell", 1}, {"maxParticlesPerCell", 1}, {"minHeight", 0},
                 {"maxHeight", 400},         {"start", "excess"},        {"temperatureExcess", 0.8},
                 {"moistureExcess", 1.5}};
    const algo::EnvironmentProfile profile = deepConvection();
    std::size_t checked = 0;
    run(pipeline(0, 1.0, soundingAtmosphere(), emit, json::object()),
        [&](int, const CondensationData& c) {
            const VapourStatics& st = *c.particles->statics;
            for (std::size_t i = 0; i < st.size(); ++i, ++checked) {
                const double air = profile.temperature(profile.groundHeight() + st.startZ[i]);
                EXPECT_NEAR(c.particles->temperature[i], air + 0.8, 1e-4) << i;
                EXPECT_NEAR(st.dewpointOffset[i], 1.5, 1e-5) << i;
            }
        });
    EXPECT_EQ(checked, 64u);
}

TEST_F(RealAtmosphere, AProfileStartWithoutAProfileIsRefusedNamingTheInput)
{
    json emit = uniformEmission(30.0);
    emit["start"] = "convective";
    // The paper's Eq. 9 line has no profile to start against.
    try {
        run(pipeline(0, 1.0, json::object(), emit, json::object()),
            [](int, const CondensationData&) {});
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("inputs/atmosphere"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("needs an atmosphere with a profile"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(RealAtmosphere, AWeatherReportOfAStableDaySaysNoParcelRisesFreely)
{
    // An isothermal day: a lifted parcel is always colder than the air around it.
    test::TempDir dir;
    test::writeFile(dir / "stable.csv",
                    "height_m,temperature_C,dewpoint_C,pressure_hPa,wind_dir_deg,wind_speed_ms\n"
                    "0,15.0,5.0,,0,0\n10000,15.0,-5.0,,0,0\n");
    json graph =
        pipeline(0, 1.0, {{"profile", "sounding"}, {"soundingFile", (dir / "stable.csv").string()}},
                 uniformEmission(15.0), json::object());
    graph["nodes"]["report"] = {
        {"type", "WriteWeatherReport"},
        {"inputs",
         {{"condensation", "condense.condensation"}, {"atmosphere", "atmosphere.atmosphere"}}},
        {"params", {{"file", "weather.####"}}}};
    const Graph g = parseGraph(graph.dump(), "stable.json", registry);
    EvaluatorOptions options;
    options.outDir = dir.path();
    Evaluator(registry, options).cookFrames(g, 0, 0, {"report"});
    const json report = json::parse(std::ifstream(dir / "weather.0000.json"));
    EXPECT_NE(report["warning"].get<std::string>().find("no parcel from the ground reaches a "
                                                        "level of free convection (CIN"),
              std::string::npos)
        << report["warning"];
}

TEST_F(RealAtmosphere, AThermalThatReachesNoLevelOfFreeConvectionIsReportedWithItsCin)
{
    // Started 3 C colder than the air, no thermal of the unseen afternoon rises freely.
    test::TempDir dir;
    test::writeFile(dir / "unseen.csv", kUnseenSounding);
    std::ostringstream log;
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
    spdlog::default_logger()->sinks().push_back(sink);
    run(pipeline(0, 1.0, {{"profile", "sounding"}, {"soundingFile", (dir / "unseen.csv").string()}},
                 {{"start", "excess"}, {"temperatureExcess", -3.0}}, json::object()),
        [](int, const CondensationData&) {});
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink), sinks.end());
    EXPECT_NE(log.str().find("reaches no level of free convection on its own (CIN -"),
              std::string::npos)
        << log.str();
}

}  // namespace cg
