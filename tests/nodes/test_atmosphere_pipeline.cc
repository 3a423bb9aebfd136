// The stochastic atmosphere end to end: NoiseMap -> VapourEmitter -> ThermalIntegrator ->
// Condensation, through the engine.

#include <gtest/gtest.h>

#include <algorithm>

#include <tbb/global_control.h>

#include "core/CoreData.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "nodes/Builtin.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

const char* kGraph = R"({
  "cloudgraph": 1, "frames": {"start": 0, "end": 120}, "timeStep": 0.2,
  "nodes": {
    "noise": {"type": "NoiseMap", "params": {"width": 24, "height": 16, "seed": 3}},
    "atmosphere": {"type": "Atmosphere"},
    "emit": {"type": "VapourEmitter", "inputs": {"map": "noise.map"}},
    "rise": {"type": "ThermalIntegrator", "inputs": {"particles": "emit.particles", "atmosphere": "atmosphere.atmosphere"}},
    "condense": {"type": "Condensation", "inputs": {"particles": "rise.particles", "atmosphere": "atmosphere.atmosphere"}},
    "vapour": {"type": "VapourPoints", "inputs": {"condensation": "condense.condensation"}, "params": {"which": "vapour"}},
    "condensed": {"type": "VapourPoints", "inputs": {"condensation": "condense.condensation"}, "params": {"which": "condensation"}},
    "all": {"type": "VapourPoints", "inputs": {"condensation": "condense.condensation"}}
  }})";

class AtmospherePipeline : public ::testing::Test {
protected:
    void SetUp() override { registerBuiltinNodes(registry); }
    Registry registry;
};

std::shared_ptr<const VapourParticlesData> particlesOf(const OutputsPtr& out)
{
    return std::dynamic_pointer_cast<const VapourParticlesData>(out->at("particles"));
}

}  // namespace

TEST_F(AtmospherePipeline, CookingFramesCostsOneStepEach)
{
    const Graph g = parseGraph(kGraph, "atmosphere.json", registry);
    Evaluator ev(registry, {});
    ev.cookFrames(g, 0, 120, {"condense"});
    EXPECT_EQ(ev.report().cookCount("rise"), 121u);
    EXPECT_EQ(ev.report().cookCount("condense"), 121u);
    EXPECT_EQ(ev.report().cookCount("noise"), 1u);
    EXPECT_EQ(ev.report().cookCount("emit"), 1u);
}

TEST_F(AtmospherePipeline, CondensationRecordsTheFirstFrameBelowTheDewPointAndAFlatBase)
{
    const Graph g = parseGraph(kGraph, "atmosphere.json", registry);
    Evaluator ev(registry, {});
    const double dewPoint = 16.0;  // Atmosphere's default
    std::vector<std::int32_t> firstBelow;
    std::vector<float> baseHeight;
    int firstFrame = -1;
    std::shared_ptr<const CondensationData> last;
    ev.cookFrames(g, 0, 120, {"condense"}, [&](int frame, const Evaluator::FrameOutputs& out) {
        const auto p = particlesOf(out[g.indexOf("rise")]);
        if (firstBelow.empty()) {
            firstBelow.assign(p->size(), -1);
            baseHeight.assign(p->size(), 0.0f);
        }
        for (std::size_t i = 0; i < p->size(); ++i) {
            if (firstBelow[i] < 0 && p->temperature[i] < dewPoint) {
                firstBelow[i] = frame;
                baseHeight[i] = p->z[i];
                if (firstFrame < 0) firstFrame = frame;
            }
        }
        last = std::dynamic_pointer_cast<const CondensationData>(
            out[g.indexOf("condense")]->at("condensation"));
    });
    ASSERT_TRUE(last);
    ASSERT_GT(last->particles->size(), 100u);
    EXPECT_EQ(last->condensedFrame, firstBelow);
    EXPECT_EQ(last->firstFrame, firstFrame);
    EXPECT_GT(firstFrame, 0);
    EXPECT_EQ(last->condensedCount(), last->particles->size());  // all condensed by frame 120

    // The defaults follow the dry adiabat at emission, so every particle condenses at the
    // closed-form altitude (T_v_max - T_dp) / 10 C/km = 1400 m, within one step's travel.
    const float lowest = *std::min_element(baseHeight.begin(), baseHeight.end());
    const float highest = *std::max_element(baseHeight.begin(), baseHeight.end());
    EXPECT_GE(lowest, 1400.0f - 0.5f);
    EXPECT_LE(highest, 1400.0f + 40.0f);  // a step at ~120 m/s and 0.2 s travels ~24 m
}

TEST_F(AtmospherePipeline, OutputIsBitIdenticalForOneAndTwoThreads)
{
    std::vector<std::vector<float>> heights;
    std::vector<std::vector<std::int32_t>> frames;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        const Graph g = parseGraph(kGraph, "atmosphere.json", registry);
        Evaluator ev(registry, {});
        const auto out = ev.pull(g, "condense", 90);
        const auto c = std::dynamic_pointer_cast<const CondensationData>(out->at("condensation"));
        std::vector<float> h(c->particles->z);
        h.insert(h.end(), c->particles->vz.begin(), c->particles->vz.end());
        h.insert(h.end(), c->particles->temperature.begin(), c->particles->temperature.end());
        heights.push_back(std::move(h));
        frames.push_back(c->condensedFrame);
    }
    EXPECT_EQ(heights[0], heights[1]);
    EXPECT_EQ(frames[0], frames[1]);
}

TEST_F(AtmospherePipeline, VapourPointsSplitTheParticlesIntoVapourAndCondensation)
{
    const Graph g = parseGraph(kGraph, "atmosphere.json", registry);
    Evaluator ev(registry, {});
    ev.cookFrames(g, 0, 120, {"condense"});
    for (int frame : {60, 120}) {
        const auto c = std::dynamic_pointer_cast<const CondensationData>(
            ev.pull(g, "condense", frame)->at("condensation"));
        auto points = [&](const char* node) {
            return std::dynamic_pointer_cast<const CloudParticlesData>(
                ev.pull(g, node, frame)->at("particles"));
        };
        const auto vapour = points("vapour"), condensed = points("condensed"), all = points("all");
        const VapourParticlesData& v = *c->particles;
        ASSERT_EQ(all->size(), v.size());
        ASSERT_EQ(condensed->size(), c->condensedCount());
        ASSERT_EQ(vapour->size() + condensed->size(), v.size());
        if (frame == 120) {
            EXPECT_GT(condensed->size(), 0u);
        }
        std::size_t iv = 0, ic = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const float xyz[3] = {v.statics->x[i], v.statics->y[i], v.z[i]};
            const auto& part = c->condensed(i) ? condensed : vapour;
            std::size_t& k = c->condensed(i) ? ic : iv;
            for (int a = 0; a < 3; ++a) {
                ASSERT_EQ(all->positions()[3 * i + static_cast<std::size_t>(a)], xyz[a]);
                ASSERT_EQ(part->positions()[3 * k + static_cast<std::size_t>(a)], xyz[a]);
            }
            EXPECT_EQ(all->sources()[i], v.statics->id[i]);
            EXPECT_EQ(part->sources()[k], v.statics->id[i]);
            EXPECT_EQ(all->levels()[i], 0);
            ++k;
        }
    }
}

}  // namespace cg
