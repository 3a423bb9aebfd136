// Vapour emission (Sec. 5.1, Eq. 3-5) against the equations evaluated independently here.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "algo/atmosphere/VapourEmission.h"

namespace cg {

namespace {

using algo::VapourEmission;
using algo::VapourEmissionSettings;

/// Eq. 3 rounded half up, computed another way than the library: for W >= 0 round half up is
/// std::round (half away from zero), and a negative W gives no particle.
std::uint64_t expectedCount(float f, const VapourEmissionSettings& s)
{
    const double w = s.minParticlesPerCell +
                     (s.maxParticlesPerCell - s.minParticlesPerCell) * static_cast<double>(f);
    const double r = std::round(w);
    return r > 0.0 ? static_cast<std::uint64_t>(r) : 0;
}

std::vector<float> rampValues(int nx, int ny)
{
    std::vector<float> v(static_cast<std::size_t>(nx) * ny);
    for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = static_cast<float>(static_cast<double>(i) / static_cast<double>(v.size() - 1));
    return v;
}

void expectSame(const VapourEmission& a, const VapourEmission& b)
{
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.homeCell, b.homeCell);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
    EXPECT_EQ(a.vz, b.vz);
    EXPECT_EQ(a.temperature, b.temperature);
}

}  // namespace

TEST(VapourEmission, CountIsEq3RoundedHalfUp)
{
    VapourEmissionSettings s;
    s.minParticlesPerCell = 1.0;
    s.maxParticlesPerCell = 7.0;  // W_p = 1 + 6 f
    // W_p exactly x.5 (f = 0.25, 0.75), integers (f = 0, 0.5, 1), and W_p just either side
    // of 3.5 (the floats nearest 5/12 from below and above).
    const std::vector<float> values = {0.0f,   0.25f,   0.75f, 0.5f,        1.0f,
                                       0.125f, 0.0625f, 0.1f,  0.41666666f, 0.41666669f};
    const int nx = 5;
    const int ny = 2;
    std::uint64_t expected = 0;
    for (float f : values) expected += expectedCount(f, s);
    // Spelled out: 1, 2.5->3, 5.5->6, 4, 7, 1.75->2, 1.375->1, 1.6->2, 3.4999999->3, 3.5000001->4
    EXPECT_EQ(expected, 33u);
    EXPECT_EQ(algo::emissionCount(values, s), expected);

    const VapourEmission e = algo::emitVapour(nx, ny, 10.0, values, s);
    ASSERT_EQ(e.size(), expected);
    for (std::size_t c = 0; c < values.size(); ++c) {
        const auto n = static_cast<std::uint64_t>(
            std::count(e.homeCell.begin(), e.homeCell.end(), static_cast<std::uint32_t>(c)));
        EXPECT_EQ(n, expectedCount(values[c], s)) << "cell " << c;
    }
}

TEST(VapourEmission, HalfIsRoundedUpEvenBelowOne)
{
    VapourEmissionSettings s;
    s.minParticlesPerCell = 0.0;
    s.maxParticlesPerCell = 1.0;
    EXPECT_EQ(algo::cellParticleCount(0.5, s), 1u);
    EXPECT_EQ(algo::cellParticleCount(0.49999999999999994, s), 0u);  // floor(w + 0.5) says 1
    EXPECT_EQ(algo::cellParticleCount(0.0, s), 0u);
    s.minParticlesPerCell = -3.0;
    EXPECT_EQ(algo::cellParticleCount(0.0, s), 0u);  // a negative W_p emits nothing
}

TEST(VapourEmission, HeightsAndTemperaturesFollowEq4AndEq5)
{
    VapourEmissionSettings s;
    s.minParticlesPerCell = 2.0;
    s.maxParticlesPerCell = 9.0;
    s.minHeight = 20.0;
    s.maxHeight = 320.0;
    s.minTemperature = 12.0;
    s.maxTemperature = 31.5;
    s.seed = 7;
    const int nx = 13;
    const int ny = 11;
    const double cellSize = 37.5;
    const std::vector<float> values = rampValues(nx, ny);
    const VapourEmission e = algo::emitVapour(nx, ny, cellSize, values, s);
    ASSERT_EQ(e.size(), algo::emissionCount(values, s));

    for (std::size_t i = 0; i < e.size(); ++i) {
        ASSERT_EQ(e.id[i], i);
        const std::uint32_t c = e.homeCell[i];
        ASSERT_LT(c, values.size());
        if (i > 0) {
            ASSERT_LE(e.homeCell[i - 1], c) << "cells in row-major order";
        }
        const double f = values[c];
        const double z = s.minHeight + (s.maxHeight - s.minHeight) * f;
        const double t = s.maxTemperature - (s.maxTemperature - s.minTemperature) *
                                                (z - s.minHeight) / (s.maxHeight - s.minHeight);
        EXPECT_FLOAT_EQ(e.z[i], static_cast<float>(z));
        EXPECT_FLOAT_EQ(e.temperature[i], static_cast<float>(t));
        EXPECT_EQ(e.vz[i], 0.0f);

        // Strictly inside the home cell, in double, after the rounding to float.
        const int ix = static_cast<int>(c % nx);
        const int iy = static_cast<int>(c / nx);
        EXPECT_GE(static_cast<double>(e.x[i]), ix * cellSize);
        EXPECT_LT(static_cast<double>(e.x[i]), (ix + 1) * cellSize);
        EXPECT_GE(static_cast<double>(e.y[i]), iy * cellSize);
        EXPECT_LT(static_cast<double>(e.y[i]), (iy + 1) * cellSize);
    }
}

TEST(VapourEmission, PositionsStayInsideTheCellAfterFloatRounding)
{
    // Cells 1e-4 m wide near x = 100 m, where floats are 7.6e-6 m apart: rounding to float
    // often lands on a cell edge, yet every x must stay below its cell's upper edge.
    VapourEmissionSettings s;
    s.maxParticlesPerCell = 200.0;
    const int nx = 1000000;
    const double cellSize = 1e-4;
    std::vector<float> values(static_cast<std::size_t>(nx), 0.0f);
    for (int i = nx - 8; i < nx; ++i) values[static_cast<std::size_t>(i)] = 1.0f;
    const VapourEmission e = algo::emitVapour(nx, 1, cellSize, values, s);
    ASSERT_EQ(e.size(), 8u * 200u);
    for (std::size_t i = 0; i < e.size(); ++i) {
        const double lo = e.homeCell[i] * cellSize;
        EXPECT_GE(static_cast<double>(e.x[i]), lo);
        EXPECT_LT(static_cast<double>(e.x[i]), (e.homeCell[i] + 1) * cellSize);
        EXPECT_GE(static_cast<double>(e.y[i]), 0.0);
        EXPECT_LT(static_cast<double>(e.y[i]), cellSize);
    }
}

TEST(VapourEmission, EqualHeightsGiveTheWarmTemperature)
{
    VapourEmissionSettings s;
    s.minHeight = 50.0;
    s.maxHeight = 50.0;
    s.maxParticlesPerCell = 3.0;
    const VapourEmission e = algo::emitVapour(2, 1, 1.0, {0.5f, 1.0f}, s);
    ASSERT_EQ(e.size(), 5u);
    for (std::size_t i = 0; i < e.size(); ++i) {
        EXPECT_EQ(e.z[i], 50.0f);
        EXPECT_EQ(e.temperature[i], static_cast<float>(s.maxTemperature));
    }
}

TEST(VapourEmission, DefaultsGiveTheDryLapseRateSoTheCloudBaseIsFlat)
{
    // T_v + 10 degC/km * P_vz is the same for every particle: all reach T_dp at one altitude.
    const VapourEmissionSettings s;
    const VapourEmission e = algo::emitVapour(8, 8, 25.0, rampValues(8, 8), s);
    ASSERT_GT(e.size(), 0u);
    for (std::size_t i = 0; i < e.size(); ++i)
        EXPECT_NEAR(e.temperature[i] + 0.01 * e.z[i], s.maxTemperature + 0.01 * s.minHeight, 1e-5);
}

TEST(VapourEmission, SameOutputForOneAndTwoThreads)
{
    VapourEmissionSettings s;
    s.maxParticlesPerCell = 12.0;
    s.seed = 12345;
    const std::vector<float> values = rampValues(64, 48);
    VapourEmission one;
    VapourEmission two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = algo::emitVapour(64, 48, 3.0, values, s);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = algo::emitVapour(64, 48, 3.0, values, s);
    }
    ASSERT_GT(one.size(), 1000u);
    expectSame(one, two);

    // And the seed matters.
    s.seed = 12346;
    const VapourEmission other = algo::emitVapour(64, 48, 3.0, values, s);
    EXPECT_EQ(other.homeCell, one.homeCell);
    EXPECT_NE(other.x, one.x);
}

TEST(VapourEmission, ZeroMapEmitsTheMinimumInEveryCell)
{
    VapourEmissionSettings s;
    s.minParticlesPerCell = 2.0;
    s.maxParticlesPerCell = 6.0;
    const std::vector<float> zeros(12, 0.0f);
    EXPECT_EQ(algo::emissionCount(zeros, s), 24u);
    const VapourEmission e = algo::emitVapour(4, 3, 5.0, zeros, s);
    ASSERT_EQ(e.size(), 24u);
    for (std::size_t i = 0; i < e.size(); ++i) {
        EXPECT_EQ(e.homeCell[i], i / 2);
        EXPECT_EQ(e.z[i], static_cast<float>(s.minHeight));
        EXPECT_EQ(e.temperature[i], static_cast<float>(s.maxTemperature));
    }

    s.minParticlesPerCell = 0.0;
    EXPECT_EQ(algo::emissionCount(zeros, s), 0u);
    EXPECT_EQ(algo::emitVapour(4, 3, 5.0, zeros, s).size(), 0u);
}

TEST(VapourEmission, RefusesBadMaps)
{
    const VapourEmissionSettings s;
    EXPECT_THROW(algo::emitVapour(2, 2, 1.0, {0.0f, 0.5f, 1.5f, 0.0f}, s), std::invalid_argument);
    EXPECT_THROW(algo::emitVapour(2, 2, 1.0, {0.0f, 0.5f, -0.1f, 0.0f}, s), std::invalid_argument);
    EXPECT_THROW(algo::emitVapour(2, 1, 1.0, {0.0f, NAN}, s), std::invalid_argument);
    EXPECT_THROW(algo::emitVapour(2, 2, 1.0, {0.0f, 0.5f}, s), std::invalid_argument);
    EXPECT_THROW(algo::emitVapour(1, 1, 0.0, {0.5f}, s), std::invalid_argument);
    try {
        algo::emitVapour(3, 2, 1.0, {0.0f, 0.0f, 0.0f, 0.0f, 2.0f, 0.0f}, s);
        FAIL() << "expected a throw";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("cell (1, 1)"), std::string::npos) << e.what();
    }
}

}  // namespace cg
