#include "golden/GoldenStats.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/CoreData.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/CameraPath.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/CloudSources.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/data/VelocityVolume.h"

namespace cg::golden {

namespace {

void count(Stats& s, const std::string& name, std::int64_t v)
{
    s[name] = {Kind::Count, static_cast<double>(v)};
}
void mean(Stats& s, const std::string& name, double v) { s[name] = {Kind::Mean, v}; }

/// Min, max and mean of n values read by `at`, as <name>_min/_max (of `extremes`' kind:
/// Bound for metres) and <name>_mean.
template <class At>
void spread(Stats& s, const std::string& name, std::size_t n, At at, Kind extremes = Kind::Bound)
{
    if (n == 0) return;  // no bounds for nothing; the count says so
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double v = at(i);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        sum += v;
    }
    s[name + "_min"] = {extremes, lo};
    s[name + "_max"] = {extremes, hi};
    mean(s, name + "_mean", sum / static_cast<double>(n));
}

/// xyz triples: bounds and centroid per axis.
void pointStats(Stats& s, const float* xyz, std::size_t n)
{
    const char* axes[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a)
        spread(s, axes[a], n, [&](std::size_t i) {
            return static_cast<double>(xyz[3 * i + static_cast<std::size_t>(a)]);
        });
}

void cloudParticles(Stats& s, const CloudParticlesData& d)
{
    count(s, "count", static_cast<std::int64_t>(d.size()));
    std::int64_t perLevel[kMaxCloudLevel + 1] = {};
    for (std::size_t i = 0; i < d.size(); ++i)
        ++perLevel[std::min<int>(d.levels()[i], kMaxCloudLevel)];
    for (int l = 0; l <= kMaxCloudLevel; ++l)
        if (perLevel[l] > 0) count(s, "level_" + std::to_string(l) + "_count", perLevel[l]);
    pointStats(s, d.positions().data(), d.size());
}

void fogVolume(Stats& s, const FogVolumeData& d) { s = gridStats(*d.grid); }

/// The velocity grid's voxels and its mean velocity per axis, m/s.
void velocityVolume(Stats& s, const VelocityVolumeData& d)
{
    const auto n = static_cast<std::int64_t>(d.grid->activeVoxelCount());
    count(s, "active_voxels", n);
    double sum[3] = {0.0, 0.0, 0.0};
    for (auto it = d.grid->cbeginValueOn(); it; ++it)
        for (int k = 0; k < 3; ++k) sum[k] += (*it)[k];
    const char* axes[] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k)
        mean(s, std::string("mean_v") + axes[k], n > 0 ? sum[k] / static_cast<double>(n) : 0.0);
}

void image(Stats& s, const ImageData& d)
{
    count(s, "width", d.width);
    count(s, "height", d.height);
    const std::size_t pixels =
        static_cast<std::size_t>(d.width) * static_cast<std::size_t>(d.height);
    if (pixels == 0) return;
    // Eight bins of Y / (1 + Y) (Y the linear luminance): a coarse exposure-free histogram
    // that shows sky, shadowed and sunlit cloud separately.
    std::int64_t histogram[8] = {};
    double sums[4] = {};
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* px = &d.rgba[4 * p];
        for (int c = 0; c < 4; ++c) sums[c] += px[c];
        const double y = std::max(0.0, 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2]);
        histogram[std::clamp(static_cast<int>(y / (1.0 + y) * 8.0), 0, 7)] += 1;
    }
    const char* channels[] = {"r", "g", "b", "a"};
    for (int c = 0; c < 4; ++c)
        mean(s, std::string("mean_") + channels[c], sums[c] / static_cast<double>(pixels));
    for (int b = 0; b < 8; ++b) count(s, "luma_hist_" + std::to_string(b), histogram[b]);
}

void cameraPath(Stats& s, const CameraPathData& d)
{
    count(s, "keys", static_cast<std::int64_t>(d.keys.size()));
    count(s, "width", d.width);
    count(s, "height", d.height);
    const algo::CameraKey& k = d.keys.front();
    const char* axes[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        mean(s, std::string("first_position_") + axes[a], k.position[a]);
        mean(s, std::string("first_look_at_") + axes[a], k.lookAt[a]);
    }
    mean(s, "first_fov", k.fovDegrees);
}

void map2D(Stats& s, const Map2DData& d)
{
    count(s, "nx", d.nx);
    count(s, "ny", d.ny);
    mean(s, "cell_size", d.cellSize);
    spread(
        s, "value", d.values.size(),
        [&](std::size_t i) { return static_cast<double>(d.values[i]); }, Kind::Mean);
}

void vapour(Stats& s, const VapourParticlesData& d)
{
    count(s, "count", static_cast<std::int64_t>(d.size()));
    const VapourStatics& st = *d.statics;
    spread(s, "x", d.size(), [&](std::size_t i) { return static_cast<double>(st.x[i]); });
    spread(s, "y", d.size(), [&](std::size_t i) { return static_cast<double>(st.y[i]); });
    spread(s, "z", d.size(), [&](std::size_t i) { return static_cast<double>(d.z[i]); });
    spread(
        s, "vz", d.size(), [&](std::size_t i) { return static_cast<double>(d.vz[i]); }, Kind::Mean);
    spread(
        s, "temperature", d.size(),
        [&](std::size_t i) { return static_cast<double>(d.temperature[i]); }, Kind::Mean);
}

void condensation(Stats& s, const CondensationData& d)
{
    // Its particles are the integrator's output, recorded there.
    count(s, "count", static_cast<std::int64_t>(d.condensedFrame.size()));
    count(s, "condensed_count", static_cast<std::int64_t>(d.condensedCount()));
    count(s, "first_frame", d.firstFrame);
}

void primitive(Stats& s, const PrimitiveSetData& d)
{
    count(s, "frames", d.frames());
    mean(s, "frame_time", d.frameTime);
    count(s, "positions", static_cast<std::int64_t>(d.positions.size() / 3));
    if (d.frames() == 0) return;
    const int last = d.frames() - 1;
    count(s, "last_frame_count", d.count(last));
    count(s, "mid_frame_count", d.count(last / 2));
    pointStats(s, d.frame(last), d.count(last));
}

void sources(Stats& s, const CloudSourcesData& d)
{
    const algo::SourceTable& t = d.table;
    count(s, "sources", static_cast<std::int64_t>(t.sources.size()));
    count(s, "top_level", t.topLevel);
    std::int64_t perLevel[256] = {};
    double speed = 0.0, scale = 0.0;
    for (const algo::Source& src : t.sources) {
        ++perLevel[src.level];
        speed += src.speed;
        scale += src.scale;
    }
    for (int l = 0; l < 256; ++l)
        if (perLevel[l] > 0) count(s, "level_" + std::to_string(l) + "_sources", perLevel[l]);
    for (std::size_t l = 0; l < t.levelStart.size(); ++l)
        count(s, "level_" + std::to_string(l + 1) + "_start", t.levelStart[l]);
    if (t.sources.empty()) return;
    const auto n = static_cast<double>(t.sources.size());
    mean(s, "speed_mean", speed / n);
    mean(s, "scale_mean", scale / n);
}

void atmosphere(Stats& s, const AtmosphereData& d)
{
    const Atmosphere& a = d.atmosphere;
    mean(s, "ground_temperature", a.groundTemperature);
    mean(s, "environment_lapse", a.environmentLapse);
    mean(s, "dew_point", a.dewPoint);
    mean(s, "dry_lapse", a.dryLapse);
    mean(s, "moist_lapse", a.moistLapse);
    mean(s, "gravity", a.gravity);
    if (a.profile) {  // issue 14: only where a graph asks for one, so older graphs keep theirs
        count(s, "profile_levels", static_cast<std::int64_t>(a.profile->levels().size()));
        mean(s, "profile_ground", a.profile->groundHeight());
        mean(s, "profile_temperature_5km", a.environmentTemperature(5000.0));
    }
    if (!a.wind.calm()) {
        count(s, "wind_levels", static_cast<std::int64_t>(a.wind.levels().size()));
        mean(s, "wind_east_5km", a.wind.at(5000.0).east);
    }
}

void floatArray(Stats& s, const FloatArrayData& d)
{
    count(s, "count", static_cast<std::int64_t>(d.values.size()));
    double sum = 0.0;
    for (float v : d.values) sum += v;
    s["sum"] = {Kind::Sum, sum};
    spread(
        s, "value", d.values.size(),
        [&](std::size_t i) { return static_cast<double>(d.values[i]); }, Kind::Mean);
}

/// Text is file paths (under a temporary directory) or log lines: only its line count is
/// stable; the numbers it prints come from other outputs.
void text(Stats& s, const TextData& d)
{
    std::int64_t lines = 0;
    for (std::size_t i = 0; i < d.value.size(); ++i)
        if (d.value[i] == '\n' || i + 1 == d.value.size()) ++lines;
    count(s, "lines", lines);
}

template <class T, class F>
bool as(const Data& v, Stats& s, F f)
{
    const T* t = dynamic_cast<const T*>(&v);
    if (t) f(s, *t);
    return t != nullptr;
}

}  // namespace

Stats gridStats(const openvdb::FloatGrid& grid)
{
    Stats s;
    count(s, "active_voxels", static_cast<std::int64_t>(grid.activeVoxelCount()));
    count(s, "leaf_nodes", static_cast<std::int64_t>(grid.tree().leafCount()));
    mean(s, "voxel_size", grid.voxelSize()[0]);
    // Ten bins of density over [0, 1]: where the volume is thin and where it is opaque.
    std::int64_t histogram[10] = {};
    double sum = 0.0, maxValue = 0.0;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const double v = *it;
        const auto n = static_cast<std::int64_t>(it.getVoxelCount());
        sum += v * static_cast<double>(n);
        maxValue = std::max(maxValue, v);
        histogram[std::clamp(static_cast<int>(std::floor(v * 10.0)), 0, 9)] += n;
    }
    s["value_sum"] = {Kind::Sum, sum};
    mean(s, "value_max", maxValue);
    for (int b = 0; b < 10; ++b) count(s, "density_hist_" + std::to_string(b), histogram[b]);
    if (grid.activeVoxelCount() == 0) return s;
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    const char* axes[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        count(s, std::string("index_min_") + axes[a], box.min()[a]);
        count(s, std::string("index_max_") + axes[a], box.max()[a]);
    }
    return s;
}

Stats statsOf(const Data& v)
{
    Stats s;
    const bool known =
        as<CloudParticlesData>(v, s, cloudParticles) || as<FogVolumeData>(v, s, fogVolume) ||
        as<VelocityVolumeData>(v, s, velocityVolume) || as<ImageData>(v, s, image) ||
        as<Map2DData>(v, s, map2D) || as<CameraPathData>(v, s, cameraPath) ||
        as<VapourParticlesData>(v, s, vapour) || as<CondensationData>(v, s, condensation) ||
        as<PrimitiveSetData>(v, s, primitive) || as<CloudSourcesData>(v, s, sources) ||
        as<AtmosphereData>(v, s, atmosphere) || as<FloatArrayData>(v, s, floatArray) ||
        as<TextData>(v, s, text) ||
        as<IntData>(v, s, [](Stats& o, const IntData& d) { count(o, "value", d.value); }) ||
        as<FloatData>(v, s, [](Stats& o, const FloatData& d) { mean(o, "value", d.value); });
    if (!known)
        throw std::runtime_error("no golden statistics for port type '" + v.typeName() +
                                 "': add them in tests/golden/GoldenStats.cc");
    return s;
}

}  // namespace cg::golden
