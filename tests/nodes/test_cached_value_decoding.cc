// Decoding cached values: every registered data type round-trips a realistic value, and
// refuses forged bytes (valid checksums, altered contents) that would break an invariant its
// consumers rely on, with a std::exception naming the type and the problem.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <openvdb/io/Stream.h>
#include <openvdb/math/Transform.h>
#include <openvdb/tools/Count.h>
#include <openvdb/tools/Prune.h>

#include "algo/atmosphere/VapourEmission.h"
#include "algo/mapping/Mapping.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/volume/Voxelize.h"
#include "core/CoreData.h"
#include "core/Registry.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/CloudSources.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/FogVolumeCodec.h"
#include "nodes/data/Image.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/mapping/MappingViews.h"

namespace cg {

namespace {

using Bytes = std::vector<unsigned char>;

const Registry& types()
{
    static const Registry* registry = [] {
        auto* r = new Registry;
        registerCoreDataTypes(*r);
        registerNodeDataTypes(*r);
        return r;
    }();
    return *registry;
}

Bytes encode(const Data& value)
{
    ByteWriter out;
    EXPECT_TRUE(value.serialize(out)) << value.typeName();
    return out.buffer();
}

/// Decodes as the disk cache does; the whole payload must be read.
DataPtr decode(const std::string& type, const Bytes& bytes)
{
    const DataTypeInfo* info = types().findDataType(type);
    if (!info) throw std::logic_error("no data type " + type);
    ByteReader in(bytes.data(), bytes.size());
    DataPtr value = info->deserialize(in);
    EXPECT_TRUE(in.atEnd()) << type << " left " << in.remaining() << " bytes";
    EXPECT_TRUE(value);
    return value;
}

template <class T>
std::shared_ptr<const T> roundTrip(const T& value)
{
    auto back = std::dynamic_pointer_cast<const T>(decode(value.typeName(), encode(value)));
    EXPECT_TRUE(back) << value.typeName();
    return back;
}

/// The bytes must be refused with a message naming the type and containing `why`.
void expectRefused(const std::string& type, const Bytes& bytes, const std::string& why)
{
    try {
        decode(type, bytes);
        ADD_FAILURE() << type << " accepted bytes it should refuse (" << why << ")";
    } catch (const std::exception& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(type), std::string::npos) << message;
        EXPECT_NE(message.find(why), std::string::npos)
            << "expected '" << why << "' in: " << message;
    }
}

template <class T>
Bytes podBytes(const std::vector<T>& v)
{
    ByteWriter out;
    out.podVector(v);
    return out.buffer();
}

Bytes concat(std::initializer_list<Bytes> parts)
{
    Bytes all;
    for (const Bytes& p : parts) all.insert(all.end(), p.begin(), p.end());
    return all;
}

std::uint64_t asU64(std::int64_t v) { return static_cast<std::uint64_t>(v); }

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// ---- engine types: every bit pattern is a valid value; only lengths can be wrong ----------

TEST(CachedValueDecoding, CoreTypesRoundTrip)
{
    EXPECT_EQ(roundTrip(FloatData(-2.5))->value, -2.5);
    EXPECT_TRUE(std::isnan(roundTrip(FloatData(std::nan("")))->value));  // Statistics of nothing
    EXPECT_EQ(roundTrip(IntData(-7))->value, -7);
    const std::vector<float> array{1.0f, kNaN, -3.0f};
    const auto back = roundTrip(FloatArrayData(array))->values;
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(std::memcmp(back.data(), array.data(), sizeof(float) * 3), 0);
    EXPECT_EQ(roundTrip(TextData(std::string("a\0b", 3)))->value, std::string("a\0b", 3));
}

TEST(CachedValueDecoding, CoreTypesRefuseLengthsPastTheEnd)
{
    ByteWriter w;
    w.u64(3);
    w.f64(1.0);
    EXPECT_THROW(decode("FloatArray", w.buffer()), std::runtime_error);
    ByteWriter s;
    s.u64(std::uint64_t{1} << 62);
    EXPECT_THROW(decode("Text", s.buffer()), std::runtime_error);
    EXPECT_THROW(decode("Float", Bytes(7, 0)), std::runtime_error);
}

// ---- Atmosphere ---------------------------------------------------------------------------

Bytes atmosphereBytes(std::vector<double> fields, const std::vector<double>& profile = {},
                      const std::vector<double>& wind = {})
{
    ByteWriter out;
    for (double v : fields) out.f64(v);
    out.podVector(profile);
    if (!profile.empty()) {
        out.f64(profile.front());  // the wind's top: the first level's height
        out.u64(1);                // the moist adiabat
    }
    out.podVector(wind);
    return out.buffer();
}

TEST(CachedValueDecoding, AtmosphereRoundTripsAndRefusesValuesTheNodeCannotMake)
{
    Atmosphere a;
    a.environmentLapse = 20.0 * 1e-3;  // the node's largest values pass exactly
    a.dryLapse = 50.0 * 1e-3;
    EXPECT_EQ(roundTrip(AtmosphereData(a))->atmosphere.dryLapse, a.dryLapse);

    const std::vector<double> ok{20.0, 6.4e-3, 16.0, 10e-3, 6e-3, 9.81};
    ASSERT_NO_THROW(decode("Atmosphere", atmosphereBytes(ok)));
    const char* names[] = {"ground temperature", "environment lapse rate", "dew point",
                           "dry lapse rate",     "moist lapse rate",       "gravity"};
    const double bad[] = {81.0, 0.021, -81.0, -1e-3, 0.051, 101.0};
    for (std::size_t i = 0; i < ok.size(); ++i) {
        for (double v : {bad[i], std::nan(""), double(kInf)}) {
            std::vector<double> f = ok;
            f[i] = v;
            SCOPED_TRACE(names[i]);
            expectRefused("Atmosphere", atmosphereBytes(f), names[i]);
        }
    }
}

TEST(CachedValueDecoding, AtmosphereProfileAndWindRoundTripOrAreRefused)
{
    Atmosphere a;
    a.profile =
        std::make_shared<algo::EnvironmentProfile>(algo::standardAtmosphere(25.0, 17.0, 11000.0));
    a.moistAdiabat = false;
    a.wind = algo::WindProfile({{0.0, 5.0, 0.0}, {10000.0, 20.0, -3.0}});
    const auto back = roundTrip(AtmosphereData(a))->atmosphere;
    ASSERT_TRUE(back.profile);
    EXPECT_EQ(back.profile->levels().size(), a.profile->levels().size());
    EXPECT_EQ(back.profile->temperature(5432.0), a.profile->temperature(5432.0));
    EXPECT_EQ(back.profile->pressure(5432.0), a.profile->pressure(5432.0));
    EXPECT_FALSE(back.moistAdiabat);
    EXPECT_EQ(back.profile->windTopHeight(), a.profile->windTopHeight());  // no wind: -inf
    EXPECT_EQ(back.wind.at(2500.0).east, a.wind.at(2500.0).east);

    const std::vector<double> ok{20.0, 6.4e-3, 16.0, 10e-3, 6e-3, 9.81};
    // height, T, T_d, p, wind east, wind north per level
    const std::vector<double> levels{0, 25, 17, 1000, 0, 0, 1000, 18, 12, 890, 5, 0};
    ASSERT_NO_THROW(decode("Atmosphere", atmosphereBytes(ok, levels, {0, 1, 2})));
    auto forgedLevels = [&](std::size_t i, double v, const std::string& why) {
        std::vector<double> l = levels;
        l[i] = v;
        expectRefused("Atmosphere", atmosphereBytes(ok, l), why);
    };
    forgedLevels(6, 0.0, "heights must increase");
    forgedLevels(1, kNaN, "profile temperature");
    forgedLevels(9, -1.0, "profile pressure");
    forgedLevels(10, 1e6, "profile wind");
    expectRefused("Atmosphere", atmosphereBytes(ok, {0, 25, 17, 1000, 0}), "a profile of 5 values");
    expectRefused("Atmosphere", atmosphereBytes(ok, {}, {0, 1}), "a wind profile of 2 values");
    expectRefused("Atmosphere", atmosphereBytes(ok, {}, {0, 1, 2, 0, 1, 2}),
                  "wind heights must increase");
    expectRefused("Atmosphere", atmosphereBytes(ok, {}, {0, kInf, 2}), "wind");
}

// ---- Map2D ---------------------------------------------------------------------------------

Bytes mapBytes(std::uint64_t nx, std::uint64_t ny, double cell, const std::vector<float>& values)
{
    ByteWriter out;
    out.u64(nx);
    out.u64(ny);
    out.f64(cell);
    out.podVector(values);
    return out.buffer();
}

std::vector<float> ramp(std::size_t n)
{
    std::vector<float> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<float>(i) / static_cast<float>(n - 1);
    return v;
}

TEST(CachedValueDecoding, Map2DRoundTripsAndRefusesBadSizesCellsAndDensities)
{
    const auto back = roundTrip(Map2DData(4, 3, 50.0, ramp(12)));
    EXPECT_EQ(back->nx, 4);
    EXPECT_EQ(back->ny, 3);
    EXPECT_EQ(back->values, ramp(12));

    expectRefused("Map2D", mapBytes(0, 3, 50.0, {}), "absurd");
    expectRefused("Map2D", mapBytes(std::uint64_t{1} << 31, 1, 50.0, ramp(2)), "absurd");
    expectRefused("Map2D", mapBytes(4, 3, 50.0, ramp(11)), "11 values for 4 x 3");
    for (double cell : {0.0, -1.0, std::nan(""), double(kInf)})
        expectRefused("Map2D", mapBytes(4, 3, cell, ramp(12)), "cell size");
    for (float v : {-0.01f, 1.01f, kNaN}) {
        auto values = ramp(12);
        values[5] = v;
        expectRefused("Map2D", mapBytes(4, 3, 50.0, values), "of cell 5 is outside [0, 1]");
    }
}

// ---- Image ---------------------------------------------------------------------------------

Bytes imageBytes(std::uint64_t w, std::uint64_t h, const std::vector<float>& rgba,
                 const std::vector<float>& background = {}, const std::vector<double>& camera = {},
                 const std::vector<std::vector<float>>& aovs = {{}, {}, {}, {}})
{
    ByteWriter out;
    out.bytes("CGIMAGE4", 8);
    out.u64(w);
    out.u64(h);
    out.podVector(rgba);
    out.podVector(background);
    out.u64(camera.empty() ? 0 : 1);
    for (double v : camera) out.f64(v);
    for (const std::vector<float>& a : aovs) out.podVector(a);
    return out.buffer();
}

TEST(CachedValueDecoding, ImageAovsRoundTripAndBadOnesAreRefused)
{
    const std::vector<float> rgba(2 * 3 * 4, 0.5f);
    ImageAovs aovs;
    for (int i = 0; i < 18; ++i) aovs.sun.push_back(0.01f * static_cast<float>(i));
    aovs.sky.assign(18, 0.25f);
    aovs.depth = {100, 200, 300, 400, 500, algo::kNoDepth};
    aovs.shadow = {0, 0.5f, 1, 0, 0, 0};
    const auto back = roundTrip(ImageData(2, 3, rgba, {}, std::nullopt, aovs));
    EXPECT_EQ(back->aovs.sun, aovs.sun);
    EXPECT_EQ(back->aovs.sky, aovs.sky);
    EXPECT_EQ(back->aovs.depth, aovs.depth);
    EXPECT_EQ(back->aovs.shadow, aovs.shadow);

    // One AOV short, or a NaN in one: refused, naming it.
    expectRefused("Image",
                  imageBytes(2, 3, rgba, {}, {}, {aovs.sun, aovs.sky, {1, 2}, aovs.shadow}),
                  "AOVs' sizes");
    std::vector<float> nan = aovs.shadow;
    nan[4] = std::nanf("");
    expectRefused("Image", imageBytes(2, 3, rgba, {}, {}, {aovs.sun, aovs.sky, aovs.depth, nan}),
                  "shadow channel 0 of pixel 4");
}

TEST(CachedValueDecoding, ImageRoundTripsAndRefusesBadSizesAndNonFinitePixels)
{
    std::vector<float> rgba(2 * 3 * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = 0.1f * static_cast<float>(i);
    const auto back = roundTrip(ImageData(2, 3, rgba));
    EXPECT_EQ(back->rgba, rgba);
    EXPECT_FALSE(back->hasBackground());

    expectRefused("Image", imageBytes(0, 3, {}), "absurd");
    expectRefused("Image", imageBytes(std::uint64_t{1} << 21, 1, rgba), "absurd");
    expectRefused("Image", imageBytes(3, 3, rgba), "24 floats for 3 x 3");
    for (float v : {kNaN, kInf}) {
        auto bad = rgba;
        bad[9] = v;
        expectRefused("Image", imageBytes(2, 3, bad), "channel 1 of pixel 2 is not finite");
    }
}

TEST(CachedValueDecoding, ImageWithABackgroundRoundTripsAndRefusesAWrongBackground)
{
    std::vector<float> rgba(2 * 3 * 4), background(2 * 3 * 3);
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = 0.1f * static_cast<float>(i);
    for (std::size_t i = 0; i < background.size(); ++i)
        background[i] = 0.5f + 0.01f * static_cast<float>(i);
    const auto back = roundTrip(ImageData(2, 3, rgba, background));
    EXPECT_EQ(back->rgba, rgba);
    EXPECT_EQ(back->background, background);

    // One pixel short, or RGBA where RGB belongs: refused, never read past.
    expectRefused("Image", imageBytes(2, 3, rgba, std::vector<float>(15, 0.5f)),
                  "15 background floats for 2 x 3 RGB pixels");
    expectRefused("Image", imageBytes(2, 3, rgba, std::vector<float>(24, 0.5f)),
                  "24 background floats for 2 x 3 RGB pixels");
    for (float v : {kNaN, kInf}) {
        auto bad = background;
        bad[7] = v;
        expectRefused("Image", imageBytes(2, 3, rgba, bad),
                      "background channel 1 of pixel 2 is not finite");
    }
    // A version 1 entry (untagged: the width first, no background) is not misread.
    ByteWriter v1;
    v1.u64(2);
    v1.u64(3);
    v1.podVector(rgba);
    expectRefused("Image", v1.buffer(), "not a version 4 image");
}

TEST(CachedValueDecoding, ImageCameraRoundTripsAndRefusesAnUnusableCamera)
{
    const std::vector<float> rgba(2 * 3 * 4, 0.25f);
    algo::RenderCamera camera;
    camera.position = {1.5, -2000.25, 300.0};
    camera.lookAt = {10.0, 20.0, 1000.0};
    camera.up = {0.1, 0.0, 1.0};
    camera.fovDegrees = 37.5;
    const auto back = roundTrip(ImageData(2, 3, rgba, {}, camera));
    ASSERT_TRUE(back->camera.has_value());
    EXPECT_EQ(back->camera->position, camera.position);
    EXPECT_EQ(back->camera->lookAt, camera.lookAt);
    EXPECT_EQ(back->camera->up, camera.up);
    EXPECT_EQ(back->camera->fovDegrees, camera.fovDegrees);
    EXPECT_EQ(back->camera->width, 2);
    EXPECT_EQ(back->camera->height, 3);

    const std::vector<double> good = {0, 0, 0, 0, 1, 0, 0, 0, 1, 40};
    auto bad = good;
    bad[10 - 1] = 180.0;
    expectRefused("Image", imageBytes(2, 3, rgba, {}, bad), "field of view");
    bad = good;
    bad[4] = kNaN;
    expectRefused("Image", imageBytes(2, 3, rgba, {}, bad), "not finite");
    bad = good;
    bad[3] = 0, bad[4] = 0, bad[5] = 0;
    expectRefused("Image", imageBytes(2, 3, rgba, {}, bad), "looks at its own position");
}

// ---- PrimitiveSet --------------------------------------------------------------------------

Bytes primitiveBytes(double frameTime, const std::vector<std::uint32_t>& counts,
                     const std::vector<float>& positions)
{
    ByteWriter out;
    out.f64(frameTime);
    out.podVector(counts);
    out.podVector(positions);
    return out.buffer();
}

/// N_f(s) = 3 + 2 s particles on a spiral that rises with s.
PrimitiveSetData makePrimitive(int frames)
{
    std::vector<std::uint32_t> counts;
    std::vector<float> positions;
    for (int s = 0; s < frames; ++s) {
        counts.push_back(static_cast<std::uint32_t>(3 + 2 * s));
        for (std::uint32_t i = 0; i < counts.back(); ++i)
            positions.insert(
                positions.end(),
                {std::sin(0.7f * static_cast<float>(i)) * (1.0f + static_cast<float>(s)),
                 std::cos(0.3f * static_cast<float>(i)) * (1.0f + static_cast<float>(s)),
                 0.5f * static_cast<float>(s) + 0.1f * static_cast<float>(i)});
    }
    return PrimitiveSetData(0.25, std::move(counts), std::move(positions));
}

TEST(CachedValueDecoding, PrimitiveSetRoundTripsAndRefusesInconsistentFrames)
{
    const PrimitiveSetData p = makePrimitive(6);
    const auto back = roundTrip(p);
    EXPECT_EQ(back->counts, p.counts);
    EXPECT_EQ(back->positions, p.positions);
    EXPECT_EQ(back->frame(5), back->positions.data() + 3 * (3 + 5 + 7 + 9 + 11));

    for (double t : {0.0, -1.0})
        expectRefused("PrimitiveSet", primitiveBytes(t, p.counts, p.positions),
                      "frame time must be positive");
    for (double t : {std::nan(""), double(kInf)})
        expectRefused("PrimitiveSet", primitiveBytes(t, p.counts, p.positions),
                      "frame time is not finite");
    expectRefused("PrimitiveSet", primitiveBytes(0.25, {}, {}), "no frames");
    expectRefused("PrimitiveSet", primitiveBytes(0.25, {2, 1}, std::vector<float>(9)),
                  "decreases at frame 1");
    expectRefused("PrimitiveSet", primitiveBytes(0.25, {1, 2}, std::vector<float>(6)),
                  "positions do not match");
    expectRefused("PrimitiveSet", primitiveBytes(0.25, {1}, std::vector<float>(4)),
                  "positions do not match");
    // Counts whose sum wraps around 2^64 to the number of positions given.
    std::vector<std::uint32_t> huge(std::size_t{1} << 20, 0xffffffffu);
    expectRefused("PrimitiveSet", primitiveBytes(0.25, huge, std::vector<float>(3)),
                  "positions do not match");
    for (float v : {kNaN, -kInf}) {
        auto positions = p.positions;
        positions[7] = v;
        expectRefused("PrimitiveSet", primitiveBytes(0.25, p.counts, positions),
                      "coordinate 7 is not finite");
    }
}

// ---- CloudParticles ------------------------------------------------------------------------

TEST(CachedValueDecoding, CloudParticlesRoundTripAndRefuseBadLevelsAndLengths)
{
    const std::vector<float> positions{0, 1, 2, 3, 4, kNaN};  // may honestly be non-finite
    std::vector<float> origins(30, 0.0f);
    origins[27] = 5.0f, origins[29] = -2.5f;  // source 9's copy
    const CloudParticlesData c(positions, std::vector<std::uint8_t>{0, kMaxCloudLevel},
                               std::vector<std::uint32_t>{7, 9}, origins);
    const auto back = roundTrip(c);
    EXPECT_EQ(std::vector<std::uint8_t>(back->levels()),
              (std::vector<std::uint8_t>{0, kMaxCloudLevel}));
    EXPECT_EQ(std::vector<std::uint32_t>(back->sources()), (std::vector<std::uint32_t>{7, 9}));
    EXPECT_EQ(std::vector<float>(back->copyOrigins()), origins);

    const auto payload = [&](const std::vector<std::uint8_t>& levels,
                             const std::vector<std::uint32_t>& sources,
                             const std::vector<float>& copyOrigins) {
        return concat(
            {podBytes(positions), podBytes(levels), podBytes(sources), podBytes(copyOrigins)});
    };
    ASSERT_NO_THROW(decode("CloudParticles", payload({1, 2}, {0, 1}, {})));
    ASSERT_NO_THROW(decode("CloudParticles", payload({1, 2}, {0, 1}, std::vector<float>(6, 1.0f))));
    expectRefused("CloudParticles", payload({1, kMaxCloudLevel + 1}, {0, 1}, {}),
                  "particle 1 has level 33");
    expectRefused("CloudParticles", payload({1}, {0}, {}), "arrays differ in length");
    expectRefused("CloudParticles", payload({1, 2}, {0}, {}), "arrays differ in length");
    expectRefused("CloudParticles", payload({1, 2}, {0, 1}, std::vector<float>(4, 1.0f)),
                  "copy origins are not xyz triples");
    expectRefused("CloudParticles", payload({1, 2}, {0, 2}, std::vector<float>(6, 1.0f)),
                  "particle 1 names source 2, which has no copy origin");
    // The version 1 payload (no copy origins) is refused, not misread.
    expectRefused("CloudParticles",
                  concat({podBytes(positions), podBytes(std::vector<std::uint8_t>{1, 2}),
                          podBytes(std::vector<std::uint32_t>{0, 1})}),
                  "truncated payload");
    ByteWriter huge;  // a count checked before allocating
    huge.u64(std::uint64_t{1} << 60);
    expectRefused("CloudParticles", huge.buffer(), "truncated payload");
}

// ---- VapourParticles and Condensation ------------------------------------------------------

/// Vapour emitted from an 8 x 8 ramp map of 100 m cells (as VapourEmitter does).
algo::VapourEmission emitted()
{
    algo::VapourEmissionSettings s;
    s.maxParticlesPerCell = 3.0;
    return algo::emitVapour(8, 8, 100.0, ramp(64), s);
}

struct VapourFields {
    std::vector<std::uint32_t> id, homeCell;
    std::vector<float> x, y, z, vz, t;
    std::vector<float> startZ, dewpointOffset, releaseTime, movedX, movedY, movedVx, movedVy;
};

VapourFields vapourFields()
{
    algo::VapourEmission e = emitted();
    return {e.id, e.homeCell, e.x, e.y, e.z, e.vz, e.temperature, e.z, {}, {}, {}, {}, {}, {}};
}

Bytes vapourBytes(const VapourFields& f)
{
    ByteWriter out;
    out.podVector(f.id);
    out.podVector(f.homeCell);
    out.podVector(f.x);
    out.podVector(f.y);
    out.podVector(f.startZ);
    out.podVector(f.dewpointOffset);
    out.podVector(f.releaseTime);
    out.podVector(f.z);
    out.podVector(f.vz);
    out.podVector(f.t);
    out.podVector(f.movedX);
    out.podVector(f.movedY);
    out.podVector(f.movedVx);
    out.podVector(f.movedVy);
    return out.buffer();
}

std::shared_ptr<const VapourParticlesData> particlesOf(const VapourFields& f)
{
    auto statics = std::make_shared<VapourStatics>();
    statics->id = f.id;
    statics->homeCell = f.homeCell;
    statics->x = f.x;
    statics->y = f.y;
    statics->startZ = f.startZ;
    statics->dewpointOffset = f.dewpointOffset;
    statics->releaseTime = f.releaseTime;
    return std::make_shared<VapourParticlesData>(statics, f.movedX, f.movedY, f.movedVx, f.movedVy,
                                                 f.z, f.vz, f.t);
}

TEST(CachedValueDecoding, VapourParticlesRoundTripAndRefuseBrokenStatics)
{
    VapourFields f = vapourFields();
    ASSERT_GT(f.id.size(), 20u);
    f.z[3] = kInf;  // the integrator may overflow: not refused
    const auto back = roundTrip(*particlesOf(f));
    EXPECT_EQ(back->statics->homeCell, f.homeCell);
    EXPECT_EQ(back->statics->x, f.x);
    EXPECT_EQ(back->temperature, f.t);
    EXPECT_FALSE(back->movedHorizontally());

    // Moved by a wind, with irregular-base offsets: both survive the round trip.
    VapourFields moved = vapourFields();
    moved.dewpointOffset.assign(moved.id.size(), -1.5f);
    moved.releaseTime.assign(moved.id.size(), 12.5f);
    moved.movedX.assign(moved.id.size(), -40.0f);  // blown off the map: not refused
    moved.movedY = moved.y;
    moved.movedVx.assign(moved.id.size(), 7.5f);
    moved.movedVy.assign(moved.id.size(), -0.25f);
    const auto movedBack = roundTrip(*particlesOf(moved));
    EXPECT_EQ(movedBack->xs(), moved.movedX);
    EXPECT_EQ(movedBack->vxs(), moved.movedVx);
    EXPECT_EQ(movedBack->vys(), moved.movedVy);
    EXPECT_EQ(movedBack->statics->x, moved.x);
    EXPECT_EQ(movedBack->statics->dewpointOffset, moved.dewpointOffset);
    EXPECT_EQ(movedBack->statics->startZ, moved.startZ);
    EXPECT_EQ(movedBack->statics->releaseTime, moved.releaseTime);

    auto forged = [&](const std::function<void(VapourFields&)>& change, const std::string& why) {
        VapourFields g = vapourFields();
        change(g);
        expectRefused("VapourParticles", vapourBytes(g), why);
    };
    forged([](VapourFields& g) { g.id[5] = 6; }, "particle 5 has id 6");
    forged([](VapourFields& g) { g.homeCell[9] = g.homeCell[10] + 1; },
           "not in emission order at particle 10");
    forged([](VapourFields& g) { g.x[4] = -1.0f; }, "particle 4 is not on the map");
    forged([](VapourFields& g) { g.y[4] = kNaN; }, "particle 4 is not on the map");
    forged([](VapourFields& g) { g.x[4] = kInf; }, "particle 4 is not on the map");
    forged([](VapourFields& g) { g.vz.pop_back(); }, "particle arrays differ in length");
    forged([](VapourFields& g) { g.homeCell.pop_back(); }, "particle arrays differ in length");
    forged([](VapourFields& g) { g.startZ.pop_back(); }, "particle arrays differ in length");
    forged([](VapourFields& g) { g.movedX = g.x; }, "particle arrays differ in length");
    forged([](VapourFields& g) { g.dewpointOffset = {1.0f}; }, "particle arrays differ in length");
    forged([](VapourFields& g) { g.startZ[6] = kNaN; }, "particle 6 has no finite start");
    forged(
        [](VapourFields& g) {
            g.dewpointOffset.assign(g.id.size(), 0.0f);
            g.dewpointOffset[2] = kInf;
        },
        "particle 2 has no finite start");
    forged(
        [](VapourFields& g) {
            g.releaseTime.assign(g.id.size(), 1.0f);
            g.releaseTime[3] = -1.0f;
        },
        "particle 3 has no finite start");
    forged([](VapourFields& g) { g.releaseTime = {1.0f}; }, "particle arrays differ in length");
    forged([](VapourFields& g) { g.movedVx = {1.0f}; }, "particle arrays differ in length");
    forged(
        [](VapourFields& g) {
            g.movedVx = g.x;
            g.movedVy = {};
        },
        "particle arrays differ in length");
}

/// A condensation height for each condensation frame: 1000 m + 10 m a frame, NaN for -1.
std::vector<float> heightsOf(const std::vector<std::int32_t>& frames)
{
    std::vector<float> heights;
    for (std::int32_t f : frames)
        heights.push_back(f >= 0 ? 1000.0f + 10.0f * static_cast<float>(f) : kNaN);
    return heights;
}

Bytes condensationBytes(const VapourFields& f, const std::vector<std::int32_t>& frames,
                        std::int64_t first, const std::vector<float>& heights)
{
    return concat({vapourBytes(f), podBytes(frames), podBytes(heights), [&] {
                       ByteWriter out;
                       out.u64(asU64(first));
                       return out.buffer();
                   }()});
}

Bytes condensationBytes(const VapourFields& f, const std::vector<std::int32_t>& frames,
                        std::int64_t first)
{
    return condensationBytes(f, frames, first, heightsOf(frames));
}

TEST(CachedValueDecoding, CondensationRoundTripsAndRefusesInconsistentFrames)
{
    const VapourFields f = vapourFields();
    std::vector<std::int32_t> frames(f.id.size(), -1);
    frames[2] = 7;
    frames[4] = 5;
    const auto back = roundTrip(CondensationData(particlesOf(f), frames, heightsOf(frames), 5));
    EXPECT_EQ(back->condensedFrame, frames);
    EXPECT_EQ(back->condensedHeight[2], 1070.0f);
    EXPECT_TRUE(std::isnan(back->condensedHeight[3]));
    EXPECT_EQ(back->firstFrame, 5);
    EXPECT_EQ(back->particles->size(), f.id.size());
    ASSERT_NO_THROW(decode("Condensation",
                           condensationBytes(f, std::vector<std::int32_t>(f.id.size(), -1), -1)));

    auto heights = heightsOf(frames);
    heights[3] = 1200.0f;  // a height for a particle that has not condensed
    expectRefused("Condensation", condensationBytes(f, frames, 5, heights),
                  "particle 3 has condensation height 1200.000000 at condensation frame -1");
    heights = heightsOf(frames);
    heights[4] = kInf;
    expectRefused("Condensation", condensationBytes(f, frames, 5, heights),
                  "particle 4 has condensation height inf at condensation frame 5");
    heights = heightsOf(frames);
    heights.pop_back();
    expectRefused("Condensation", condensationBytes(f, frames, 5, heights), "differ in length");
    expectRefused("Condensation", condensationBytes(f, frames, 4),
                  "first condensation frame 4 but the earliest is 5");
    expectRefused("Condensation", condensationBytes(f, frames, -1),
                  "first condensation frame -1 but the earliest is 5");
    expectRefused("Condensation", condensationBytes(f, frames, -2), "first frame -2 is outside");
    expectRefused("Condensation", condensationBytes(f, frames, std::int64_t{1} << 31),
                  "first frame 2147483648 is outside");
    auto low = frames;
    low[6] = -2;
    expectRefused("Condensation", condensationBytes(f, low, 5), "particle 6 condensed at frame -2");
    auto high = frames;
    high[6] = std::numeric_limits<std::int32_t>::max();
    expectRefused("Condensation", condensationBytes(f, high, 5),
                  "particle 6 condensed at frame 2147483647");
    auto shorter = frames;
    shorter.pop_back();
    expectRefused("Condensation", condensationBytes(f, shorter, 5), "differ in length");
    VapourFields broken = f;
    broken.id[0] = 1;
    expectRefused("Condensation", condensationBytes(broken, frames, 5), "particle 0 has id 1");
}

// ---- CloudSources -------------------------------------------------------------------------

/// A mapper run over a small scene: the 8 x 8 ramp map, the emitted vapour with about four in
/// five particles condensed at frames 0..3, a 12-frame primitive.
struct MapperScene {
    Map2DData map{8, 8, 100.0, ramp(64)};
    PrimitiveSetData primitive = makePrimitive(12);
    std::shared_ptr<const CondensationData> condensation;
    algo::MappingSettings settings;
    algo::SourceTable table;

    explicit MapperScene(std::uint32_t particlesPerCopy = 0,
                         algo::Level1Origin origin = algo::Level1Origin::Particle,
                         double cloudTop = 0.0)
    {
        VapourFields f = vapourFields();
        if (origin == algo::Level1Origin::Trail)  // some rise (and lay their copies), some do not
            for (std::size_t i = 0; i < f.vz.size(); ++i) f.vz[i] = i % 3 == 0 ? 0.0f : 2.0f;
        std::vector<std::int32_t> frames(f.id.size());
        for (std::size_t i = 0; i < frames.size(); ++i)
            frames[i] = i % 5 == 0 ? -1 : static_cast<std::int32_t>(i % 4);
        condensation =
            std::make_shared<CondensationData>(particlesOf(f), frames, heightsOf(frames), 0);
        settings.maxLevel = 3;
        settings.selectionRatio = {0.25, 0.05};
        settings.levelDelay = 4;
        settings.windowLength = {6, 5};
        settings.metresPerPrimitiveMetre = 3.0;
        settings.timeStep = 0.5;
        settings.seed = 11;
        settings.particlesPerCopy = particlesPerCopy;
        settings.level1Origin = origin;
        settings.trailRiseSpeed = 0.5;
        settings.cloudTop = cloudTop;
        const PrimitiveViewHolder prim(primitive);
        for (int frame = 0; frame <= 16; ++frame)
            table = algo::stepSources(table, frame, condensation->firstFrame,
                                      condensationView(*condensation), mapView(map), prim.view,
                                      settings);
    }

    /// Index of the first record of `level`.
    std::size_t first(int level) const
    {
        for (std::size_t j = 0; j < table.sources.size(); ++j)
            if (table.sources[j].level == level) return j;
        throw std::logic_error("no record of level " + std::to_string(level));
    }
    Bytes bytes() const { return encode(CloudSourcesData(table, settings)); }
};

/// Byte offset of field `field` (0 level .. 6 scale, 7 flatten) of record j in CloudSources'
/// bytes.
std::size_t fieldAt(std::size_t j, std::size_t field) { return 8 + 64 * j + 8 * field; }

void patchU64(Bytes& b, std::size_t at, std::uint64_t v)
{
    for (int i = 0; i < 8; ++i)
        b[at + static_cast<std::size_t>(i)] = static_cast<unsigned char>(v >> (8 * i));
}

TEST(CachedValueDecoding, CloudSourcesRoundTripAMapperRun)
{
    for (std::uint32_t perCopy : {0u, 12u}) {
        MapperScene scene(perCopy);
        // The rules that place the particles travel with the table (GenerateCloud reads them).
        if (perCopy > 0) {
            scene.settings.parentRule = algo::ParentRule::PerParticle;
            scene.settings.pastLastFrame = algo::PastLastFrame::Hold;
            scene.settings.level1Origin = algo::Level1Origin::CondensationLevel;
        }
        for (int level = 1; level <= 3; ++level) ASSERT_NO_THROW(scene.first(level)) << level;
        ASSERT_FALSE(scene.table.cloudTaken.empty());
        const auto back = roundTrip(CloudSourcesData(scene.table, scene.settings));
        ASSERT_EQ(back->table.sources.size(), scene.table.sources.size());
        for (std::size_t j = 0; j < scene.table.sources.size(); ++j) {
            const algo::Source& a = scene.table.sources[j];
            const algo::Source& b = back->table.sources[j];
            EXPECT_TRUE(a.level == b.level && a.phase == b.phase && a.parent == b.parent &&
                        a.parentFluid == b.parentFluid && a.startFrame == b.startFrame &&
                        a.speed == b.speed && a.scale == b.scale)
                << "record " << j;
        }
        EXPECT_EQ(back->table.topLevel, scene.table.topLevel);
        EXPECT_EQ(back->table.levelStart, scene.table.levelStart);
        EXPECT_EQ(back->table.condensationTaken, scene.table.condensationTaken);
        EXPECT_EQ(back->table.cloudTaken, scene.table.cloudTaken);
        EXPECT_EQ(back->settings.selectionRatio, scene.settings.selectionRatio);
        EXPECT_EQ(back->settings.windowLength, scene.settings.windowLength);
        EXPECT_EQ(back->settings.seed, scene.settings.seed);
        EXPECT_EQ(back->settings.parentRule, scene.settings.parentRule);
        EXPECT_EQ(back->settings.pastLastFrame, scene.settings.pastLastFrame);
        EXPECT_EQ(back->settings.level1Origin, scene.settings.level1Origin);
        EXPECT_TRUE(back->table.anchors.empty());
        EXPECT_NO_THROW(
            checkSourcesFit(back->table, back->settings, *scene.condensation, scene.primitive));
    }
}

/// Particles drawn for copies the cloud top refused stay taken without records: the table
/// still round-trips, and a cloud top under every copy ends the selection instead of probing
/// for a free particle forever.
TEST(CachedValueDecoding, CloudSourcesRoundTripTablesWithCopiesTheCloudTopRefused)
{
    const auto refusedLevelOne = [](const MapperScene& scene) {
        std::size_t taken = 0, levelOne = 0;
        for (std::uint8_t t : scene.table.condensationTaken) taken += t;
        for (const algo::Source& src : scene.table.sources) levelOne += src.level == 1;
        return taken - levelOne;
    };
    const MapperScene none(0, algo::Level1Origin::Particle, 1e-3);  // under every origin
    EXPECT_TRUE(none.table.sources.empty());
    EXPECT_GT(refusedLevelOne(none), 0u);
    std::size_t partly = 0;
    for (double top : {5.0, 10.0, 20.0, 40.0, 80.0, 160.0}) {
        const MapperScene scene(0, algo::Level1Origin::Particle, top);
        if (refusedLevelOne(scene) == 0 || scene.table.sources.empty()) continue;
        ++partly;
        const auto back = roundTrip(CloudSourcesData(scene.table, scene.settings));
        EXPECT_EQ(back->table.condensationTaken, scene.table.condensationTaken) << top;
        EXPECT_EQ(back->table.cloudTaken, scene.table.cloudTaken) << top;
        EXPECT_EQ(back->table.sources.size(), scene.table.sources.size()) << top;
    }
    EXPECT_GT(partly, 0u) << "no cloud top refused some copies and kept others";
    const auto back = roundTrip(CloudSourcesData(none.table, none.settings));
    EXPECT_EQ(back->table.condensationTaken, none.table.condensationTaken);
}

TEST(CachedValueDecoding, CloudSourcesRoundTripTrailAnchors)
{
    const MapperScene scene(0, algo::Level1Origin::Trail);
    const auto& a = scene.table.anchors;
    ASSERT_EQ(a.size(), 3 * scene.table.sources.size());
    std::size_t laid = 0, riding = 0;
    for (std::size_t j = 0; j < scene.table.sources.size(); ++j)
        if (scene.table.sources[j].level == 1) (std::isnan(a[3 * j]) ? riding : laid) += 1;
    ASSERT_GT(laid, 0u);
    ASSERT_GT(riding, 0u);
    const auto back = roundTrip(CloudSourcesData(scene.table, scene.settings));
    ASSERT_EQ(back->table.anchors.size(), a.size());
    EXPECT_EQ(std::memcmp(back->table.anchors.data(), a.data(), a.size() * sizeof(float)),
              0);  // NaNs too
    EXPECT_EQ(back->settings.level1Origin, algo::Level1Origin::Trail);
    EXPECT_EQ(back->settings.trailRiseSpeed, scene.settings.trailRiseSpeed);
}

using TableChange = std::function<void(MapperScene&)>;

void expectSourcesRefused(const TableChange& change, const std::string& why,
                          std::uint32_t perCopy = 0)
{
    MapperScene scene(perCopy);
    change(scene);
    SCOPED_TRACE(why);
    expectRefused("CloudSources", scene.bytes(), why);
}

TEST(CachedValueDecoding, CloudSourcesRefuseSettingsTheMapperCannotHave)
{
    using S = MapperScene;
    expectSourcesRefused([](S& s) { s.settings.maxLevel = 0; }, "maxLevel 0 is outside");
    expectSourcesRefused([](S& s) { s.settings.maxLevel = 33; }, "maxLevel 33 is outside");
    expectSourcesRefused([](S& s) { s.settings.selectionRatio = {}; }, "0 selection ratios");
    expectSourcesRefused([](S& s) { s.settings.selectionRatio.assign(33, 0.1); },
                         "33 selection ratios");
    expectSourcesRefused([](S& s) { s.settings.selectionRatio[1] = 1.5; }, "selection ratio 1.5");
    expectSourcesRefused([](S& s) { s.settings.selectionRatio[0] = std::nan(""); },
                         "selection ratio nan");
    expectSourcesRefused([](S& s) { s.settings.windowLength = {}; }, "0 window lengths");
    expectSourcesRefused([](S& s) { s.settings.windowLength.assign(33, 5); }, "33 window lengths");
    expectSourcesRefused([](S& s) { s.settings.windowLength[1] = -1; }, "window length -1");
    expectSourcesRefused([](S& s) { s.settings.windowLength[0] = 2000000000; },
                         "window length 2000000000");
    expectSourcesRefused([](S& s) { s.settings.firstStart = -2; }, "firstStart -2");
    expectSourcesRefused([](S& s) { s.settings.levelDelay = -1; }, "levelDelay -1");
    expectSourcesRefused([](S& s) { s.settings.scaleCoefficient = std::nan(""); },
                         "scaleCoefficient");
    expectSourcesRefused([](S& s) { s.settings.speedCoefficient = 1e4; }, "speedCoefficient");
    expectSourcesRefused([](S& s) { s.settings.metresPerPrimitiveMetre = 0.0; },
                         "metresPerPrimitiveMetre");
    expectSourcesRefused([](S& s) { s.settings.timeStep = 0.0; }, "time step");  // a zero interval
    expectSourcesRefused([](S& s) { s.settings.timeStep = double(kInf); }, "time step");
    expectSourcesRefused([](S& s) { s.settings.maxSources = 0; }, "maxSources 0");
    expectSourcesRefused([](S& s) { s.settings.maxSources = s.table.sources.size() - 1; },
                         "over maxSources");
    expectSourcesRefused([](S& s) { s.settings.particlesPerCopy = (1u << 30) + 1; },
                         "particlesPerCopy");
    expectSourcesRefused([](S& s) { s.settings.parentRule = static_cast<algo::ParentRule>(2); },
                         "parentRule 2 is above 1");
    expectSourcesRefused(
        [](S& s) { s.settings.pastLastFrame = static_cast<algo::PastLastFrame>(7); },
        "pastLastFrame 7 is above 1");
    expectSourcesRefused([](S& s) { s.settings.level1Origin = static_cast<algo::Level1Origin>(3); },
                         "level1Origin 3 is above 2");
    expectSourcesRefused([](S& s) { s.settings.trailRiseSpeed = -1.0; }, "trailRiseSpeed");
    expectSourcesRefused([](S& s) { s.settings.trailRiseSpeed = double(kInf); }, "trailRiseSpeed");
    // Trail anchors: one triple per record, whole (all finite or all NaN) on level 1, zero deeper.
    expectSourcesRefused([](S& s) { s.settings.level1Origin = algo::Level1Origin::Trail; },
                         "0 anchor values for");
    expectSourcesRefused([](S& s) { s.table.anchors.assign(3, 1.0f); },
                         "3 anchor values for 0 trail");
    const auto trail = [](const TableChange& change) {
        return [change](S& s) {
            s.settings.level1Origin = algo::Level1Origin::Trail;
            s.table.anchors.assign(3 * s.table.sources.size(), 0.0f);
            change(s);
        };
    };
    expectSourcesRefused(trail([](S& s) { s.table.anchors[3 * s.first(1) + 1] = NAN; }),
                         "does not fit a level 1");
    expectSourcesRefused(trail([](S& s) { s.table.anchors[3 * s.first(1)] = kInf; }),
                         "does not fit a level 1");
    expectSourcesRefused(trail([](S& s) { s.table.anchors[3 * s.first(2) + 2] = 5.0f; }),
                         "does not fit a level 2");
}

TEST(CachedValueDecoding, CloudSourcesRefuseFieldsThatDoNotFit)
{
    const MapperScene scene;
    const std::size_t j = scene.first(2);
    auto patched = [&](std::size_t field, std::uint64_t v) {
        Bytes b = scene.bytes();
        patchU64(b, fieldAt(j, field), v);
        return b;
    };
    expectRefused("CloudSources", patched(0, 256 + 2), "level 258 is above 255");
    expectRefused("CloudSources", patched(1, 65536), "phase 65536 is above 65535");
    expectRefused("CloudSources", patched(2, std::uint64_t{1} << 32), "parent 4294967296 is above");
    expectRefused("CloudSources", patched(3, std::uint64_t{1} << 32),
                  "parent fluid id 4294967296 is above");
    expectRefused("CloudSources", patched(4, asU64(-5)), "start frame -5 is outside");
    expectRefused("CloudSources", patched(4, std::uint64_t{1} << 31),
                  "start frame 2147483648 is outside");
    double speed = 1.1;  // not a float: a widened float never looks like this
    std::uint64_t bits;
    std::memcpy(&bits, &speed, 8);
    expectRefused("CloudSources", patched(5, bits), "speed 1.100000 is not a 32-bit float");
    expectRefused("CloudSources", patched(7, bits), "flatten 1.100000 is not a 32-bit float");
    Bytes count = scene.bytes();
    patchU64(count, 0, scene.table.sources.size() + 1000);
    expectRefused("CloudSources", count, "record count runs past the end");
}

TEST(CachedValueDecoding, CloudSourcesRefuseInconsistentRecords)
{
    using S = MapperScene;
    expectSourcesRefused([](S& s) { s.table.topLevel = 0; }, "L_max 0 is outside");
    expectSourcesRefused([](S& s) { s.table.topLevel = 4; }, "L_max 4 is outside 1..3");
    expectSourcesRefused([](S& s) { s.table.levelStart.pop_back(); },
                         "2 level starts for 3 levels");
    expectSourcesRefused([](S& s) { s.table.levelStart[2] += 1; }, "t_s[3] = ");
    expectSourcesRefused([](S& s) { s.table.levelStart.assign(3, -2); }, "t_s[1] = -2");
    expectSourcesRefused([](S& s) { s.settings.firstStart = s.table.levelStart[0] + 1; },
                         "t_s[1] = 0 is not one");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(2)].level = 0; },
                         "level 0 is outside 1..3");
    expectSourcesRefused([](S& s) { s.table.topLevel = 2; }, "level 3 is outside 1..2");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(2)].flatten = 0.05f; },
                         "flatten 0.050000 is outside [0.100000, 1]");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(2)].flatten = 1.5f; },
                         "flatten 1.500000 is outside");
    expectSourcesRefused([](S& s) { s.table.sources.back().startFrame = 0; },
                         "starts before the record above it");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(2)].speed = 0.5f; },
                         "speed 0.500000 is outside [1, 3");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(2)].speed = 3.5f; },
                         "speed 3.500000 is outside [1, 3");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(1)].speed = kNaN; },
                         "speed nan is not a finite");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(1)].scale = -0.5f; },
                         "scale -0.500000 is outside [0, 1.5");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(1)].scale = 2.0f; },
                         "scale 2.000000 is outside [0, 1.5");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(3)].scale = kInf; },
                         "scale inf is not a finite");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(2)].phase = 1; },
                         "has a phase but copies are not thinned");
    expectSourcesRefused([](S& s) { s.table.sources[s.first(1)].parentFluid = 3; },
                         "level 1 with a parent fluid id");
    expectSourcesRefused(
        [](S& s) { s.table.sources[s.first(2)].parent = static_cast<std::uint32_t>(s.first(2)); },
        "does not precede it");
    expectSourcesRefused(
        [](S& s) { s.table.sources[s.first(3)].parent = static_cast<std::uint32_t>(s.first(1)); },
        "parent is not one level below");
}

TEST(CachedValueDecoding, CloudSourcesRefuseTakenSetsThatDisagreeWithTheRecords)
{
    using S = MapperScene;
    const auto parentOf = [](const S& s, std::size_t j) { return s.table.sources[j].parent; };
    expectSourcesRefused([&](S& s) { s.table.condensationTaken[parentOf(s, s.first(1))] = 2; },
                         "taken flag is 2");
    expectSourcesRefused([&](S& s) { s.table.condensationTaken[parentOf(s, s.first(1))] = 0; },
                         "not marked taken");
    expectSourcesRefused(
        [](S& s) {
            s.table.sources[s.first(1)].parent =
                static_cast<std::uint32_t>(s.table.condensationTaken.size());
        },
        "not marked taken");
    expectSourcesRefused(
        [&](S& s) { s.table.sources[s.first(1) + 1].parent = parentOf(s, s.first(1)); },
        "taken twice");
    expectSourcesRefused([](S& s) { s.table.cloudTaken.pop_back(); }, "cloud particles taken for");
    expectSourcesRefused([](S& s) { std::swap(s.table.cloudTaken[0], s.table.cloudTaken[1]); },
                         "not sorted and distinct");
    expectSourcesRefused([](S& s) { s.table.cloudTaken[1] = s.table.cloudTaken[0]; },
                         "not sorted and distinct");
    expectSourcesRefused(
        [](S& s) { s.table.cloudTaken.back() = std::uint64_t{s.table.sources.size()} << 32; },
        "names no record");
    // The last key moved to the last record: its child's particle is no longer marked taken.
    expectSourcesRefused(
        [](S& s) { s.table.cloudTaken.back() = std::uint64_t{s.table.sources.size() - 1} << 32; },
        "not marked taken");
}

/// Consumers check a stored table against their other inputs (the deserializer cannot).
TEST(CachedValueDecoding, CloudSourcesFitTheirInputsOrAreRefused)
{
    auto expectMisfit = [](const TableChange& change, const std::string& why) {
        MapperScene s;
        change(s);
        try {
            checkSourcesFit(s.table, s.settings, *s.condensation, s.primitive);
            ADD_FAILURE() << "accepted: " << why;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    };
    expectMisfit(
        [](MapperScene& s) {
            s.table.sources[s.first(1)].parent =
                static_cast<std::uint32_t>(s.condensation->condensedFrame.size());
        },
        "does not exist");
    expectMisfit([](MapperScene& s) { s.table.sources[s.first(1)].parent = 0; },
                 "had not condensed");  // i % 5 == 0
    expectMisfit(
        [](MapperScene& s) {
            auto frames = s.condensation->condensedFrame;
            const algo::Source& src = s.table.sources[s.first(1)];
            frames[src.parent] = src.startFrame + 1;
            s.condensation = std::make_shared<CondensationData>(s.condensation->particles, frames,
                                                                heightsOf(frames), 0);
        },
        "had not condensed when it started");
    expectMisfit([](MapperScene& s) { s.table.sources[s.first(3)].parentFluid = 1000; },
                 "is not in the primitive");
    expectMisfit(
        [](MapperScene& s) {
            // The first level-2 record's parent particle, one past N_f where it was drawn.
            algo::Source& src = s.table.sources[s.first(2)];
            const PrimitiveViewHolder prim(s.primitive);
            const double time = std::floor(algo::primitiveTime(
                s.table.sources[src.parent], src.startFrame, s.settings, prim.view));
            src.parentFluid =
                s.primitive.count(std::min(static_cast<int>(time), s.primitive.frames() - 1));
        },
        "is not in the primitive");
    expectMisfit(
        [](MapperScene& s) {
            s.table.sources[s.first(2)].parent = static_cast<std::uint32_t>(s.first(2));
        },
        "parent does not precede it");
    expectMisfit(
        [](MapperScene& s) { s.table.sources[s.table.sources[s.first(2)].parent].speed = -1.0f; },
        "primitive time is negative");
    expectMisfit([](MapperScene& s) { s.settings.primitiveCount = 2; },
                 "made with 2 primitive sets, given 1");
    const MapperScene scene;
    const PrimitiveSetData noFrames(1.0, {}, {});
    EXPECT_THROW(checkSourcesFit(scene.table, scene.settings, *scene.condensation, noFrames),
                 std::runtime_error);
}

// ---- FogVolume ----------------------------------------------------------------------------

using openvdb::Coord;
using openvdb::FloatGrid;

/// `n` particles uniform in a ball of `radius` metres around `centre` (fixed seed).
std::vector<float> ball(std::size_t n, const openvdb::Vec3d& centre, double radius,
                        std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<float> xyz;
    while (xyz.size() < 3 * n) {
        const openvdb::Vec3d p(u(rng), u(rng), u(rng));
        if (p.lengthSqr() > 1.0) continue;
        for (int a = 0; a < 3; ++a) xyz.push_back(static_cast<float>(centre[a] + radius * p[a]));
    }
    return xyz;
}

/// A Voxelizer grid with the node's metadata.
FloatGrid::Ptr voxelized(bool clamp = true)
{
    const std::vector<float> xyz = ball(3000, {120.0, -40.0, 1500.0}, 70.0, 7);
    algo::VoxelizeSettings s;
    s.voxelSize = 4.0;
    s.radius = 10.0;
    s.density = 0.3;
    s.clamp = clamp;
    FloatGrid::Ptr grid = algo::voxelizeParticles(xyz.data(), xyz.size() / 3, s);
    grid->insertMeta("frame", openvdb::Int32Metadata(-12));
    grid->insertMeta("units", openvdb::StringMetadata("metres"));
    grid->insertMeta("voxel_size_m", openvdb::DoubleMetadata(4.0));
    grid->insertMeta("particle_count", openvdb::Int64Metadata(3000));
    grid->insertMeta("flag", openvdb::BoolMetadata(true));
    grid->insertMeta("ratio", openvdb::FloatMetadata(0.1f));
    return grid;
}

/// Every value a grid holds, tile or voxel, active or not, with its state: compared bit for bit.
void expectSameGrid(const FloatGrid& a, const FloatGrid& b)
{
    EXPECT_EQ(a.getName(), b.getName());
    EXPECT_EQ(a.getGridClass(), b.getGridClass());
    EXPECT_EQ(a.background(), b.background());
    EXPECT_TRUE(a.transform() == b.transform());
    EXPECT_EQ(a.transform().mapType(), b.transform().mapType());
    EXPECT_TRUE(static_cast<const openvdb::MetaMap&>(a) == static_cast<const openvdb::MetaMap&>(b));
    EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
    EXPECT_EQ(a.tree().leafCount(), b.tree().leafCount());
    EXPECT_EQ(a.tree().nonLeafCount(), b.tree().nonLeafCount());
    EXPECT_EQ(a.tree().activeTileCount(), b.tree().activeTileCount());
    EXPECT_TRUE(a.tree().hasSameTopology(b.tree()));
    for (const auto& [from, to] : {std::make_pair(&a, &b), std::make_pair(&b, &a)}) {
        auto acc = to->getConstAccessor();
        std::size_t mismatches = 0;
        for (auto it = from->tree().cbeginValueAll(); it; ++it) {
            const float v = acc.getValue(it.getCoord());
            if (std::memcmp(&v, &*it, sizeof v) != 0 ||
                acc.isValueOn(it.getCoord()) != it.isValueOn() ||
                acc.getValueDepth(it.getCoord()) != static_cast<int>(it.getDepth()))
                ++mismatches;
        }
        EXPECT_EQ(mismatches, 0u);
    }
}

FloatGrid::Ptr decodeGrid(const Bytes& bytes)
{
    ByteReader in(bytes.data(), bytes.size());
    FloatGrid::Ptr grid = decodeFogVolume(in);
    if (!in.atEnd()) throw std::runtime_error("FogVolume: bytes left over");
    return grid;
}

Bytes encodeGrid(const FloatGrid& grid)
{
    ByteWriter out;
    if (!encodeFogVolume(grid, out)) throw std::logic_error("grid not encodable");
    return out.buffer();
}

TEST(CachedValueDecoding, FogVolumeRoundTripsAVoxelizerGridExactly)
{
    const FloatGrid::Ptr grid = voxelized();
    ASSERT_GT(grid->tree().leafCount(), 50u);
    const auto back = roundTrip(FogVolumeData(grid));
    expectSameGrid(*grid, *back->grid);
    EXPECT_EQ(back->grid->transform().mapType(), "UniformScaleMap");
}

/// Values above 1 (a water volume's extinction-scaled values, a read VDB's, unclamped sums)
/// are kept: such a volume is cached like any other, not cooked again in every process.
TEST(CachedValueDecoding, FogVolumeRoundTripsValuesAboveOneExactly)
{
    const FloatGrid::Ptr unclamped = voxelized(false);
    ASSERT_GT(openvdb::tools::minMax(unclamped->tree()).max(), 1.0f);
    unclamped->tree().addTile(1, Coord(800, 0, 0), 2.5f, true);
    expectSameGrid(*unclamped, *roundTrip(FogVolumeData(unclamped))->grid);
}

TEST(CachedValueDecoding, FogVolumeRoundTripsTilesExactly)
{
    FloatGrid::Ptr grid = voxelized();
    openvdb::FloatTree& tree = grid->tree();
    // Active tiles of every level from fill, a constant leaf pruned to a level-1 tile, an
    // inactive tile off the background, and a root tile far away.
    tree.fill(openvdb::CoordBBox(Coord(-1024, -1024, 0), Coord(-769, -897, 127)), 0.5f, true);
    tree.fill(openvdb::CoordBBox(Coord(8192, 0, 0), Coord(8192 + 4095, 4095, 4095)), 0.25f, true);
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (int k = 0; k < 8; ++k) tree.setValueOn(Coord(400 + i, 400 + j, 400 + k), 0.75f);
    openvdb::tools::prune(tree);
    tree.addTile(1, Coord(-64, -64, -64), 0.125f, false);
    tree.addTile(2, Coord(-4096, 0, 0), 1.0f, false);
    std::size_t tilesOn[4] = {0, 0, 0, 0}, tilesOff = 0;
    for (auto it = tree.cbeginValueAll(); it; ++it)
        if (!it.isVoxelValue()) it.isValueOn() ? ++tilesOn[it.getLevel()] : tilesOff += *it != 0.0f;
    ASSERT_GT(tilesOn[1], 0u);
    ASSERT_GT(tilesOn[2], 0u);
    ASSERT_GT(tilesOn[3], 0u);
    ASSERT_EQ(tilesOff, 2u);
    const auto back = roundTrip(FogVolumeData(grid));
    expectSameGrid(*grid, *back->grid);
}

TEST(CachedValueDecoding, FogVolumeRoundTripsAnEmptyGridAndOtherLinearTransforms)
{
    FloatGrid::Ptr grid = FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    const auto back = roundTrip(FogVolumeData(grid));
    expectSameGrid(*grid, *back->grid);

    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.setToRotation(openvdb::math::Vec3d(0.3, 0.4, 0.5).unit(), 0.7);
    m.preScale(openvdb::math::Vec3d(2.0, 3.0, 0.5));
    m.setTranslation(openvdb::math::Vec3d(10.0, -20.0, 300.0));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(m));
    grid->tree().setValueOn(Coord(1, 2, 3), 0.5f);
    expectSameGrid(*grid, *roundTrip(FogVolumeData(grid))->grid);
}

/// Grids the format does not hold exactly are not stored (serialize returns false).
TEST(CachedValueDecoding, FogVolumeEncoderRefusesGridsItCannotHold)
{
    auto refused = [](const FloatGrid::Ptr& g) {
        ByteWriter out;
        return !FogVolumeData(g).serialize(out);
    };
    EXPECT_FALSE(refused(voxelized()));
    auto changed = [](const std::function<void(FloatGrid&)>& change) {
        FloatGrid::Ptr g = voxelized();
        change(*g);
        return g;
    };
    EXPECT_TRUE(refused(changed([](FloatGrid& g) { g.setName("other"); })));
    EXPECT_TRUE(refused(changed([](FloatGrid& g) { g.setGridClass(openvdb::GRID_LEVEL_SET); })));
    EXPECT_TRUE(refused(changed(
        [](FloatGrid& g) { g.insertMeta("v", openvdb::Vec3DMetadata(openvdb::Vec3d(1.0))); })));
    EXPECT_TRUE(refused(changed([](FloatGrid& g) { g.tree().setValueOff(Coord(0, 0, 0), kNaN); })));
    EXPECT_TRUE(
        refused(changed([](FloatGrid& g) { g.tree().addTile(1, Coord(800, 0, 0), -2.0f, true); })));
    EXPECT_TRUE(
        refused(changed([](FloatGrid& g) { g.tree().setValueOn(Coord(1 << 30, 0, 0), 0.5f); })));
    EXPECT_TRUE(refused(
        changed([](FloatGrid& g) { g.tree().addTile(3, Coord(-(1 << 30), 0, 0), 0.5f, true); })));
    EXPECT_TRUE(refused(changed([](FloatGrid& g) {
        g.setTransform(openvdb::math::Transform::createFrustumTransform(
            openvdb::BBoxd(openvdb::Vec3d(0.0), openvdb::Vec3d(10.0)), 0.5, 2.0, 1.0));
    })));
    EXPECT_TRUE(refused(changed([](FloatGrid& g) {
        g.setTransform(openvdb::math::Transform::createLinearTransform(5e-4));
    })));
    FloatGrid::Ptr background = FloatGrid::create(0.5f);
    background->setName("density");
    background->setGridClass(openvdb::GRID_FOG_VOLUME);
    EXPECT_TRUE(refused(background));
    EXPECT_TRUE(refused(changed([](FloatGrid& g) { g.setCreator("someone"); })));  // OpenVDB's name
}

/// Builds FogVolume bytes field by field, valid by default, so a test can forge one field.
struct FogBytes {
    struct TileRec {
        std::uint64_t level;
        std::int64_t x, y, z;
        float value;
        std::uint64_t active;
    };
    struct LeafRec {
        std::int64_t x, y, z;
        std::uint64_t mask[8];
        float values[512];
    };
    std::string tag = "CGFOG001";
    double matrix[16] = {4, 0, 0, 0, 0, 4, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1};
    float background = 0.0f;
    std::vector<std::function<void(ByteWriter&)>> meta;
    std::uint64_t metaCount = 2;
    std::vector<TileRec> tiles{
        {1, 8, 0, 0, 0.5f, 1}, {2, 128, 0, 0, 0.25f, 0}, {3, 4096, 0, 0, 1.0f, 1}};
    std::vector<LeafRec> leaves;
    std::optional<std::uint64_t> tileCount, leafCount;

    FogBytes()
    {
        meta.push_back([](ByteWriter& w) { w.str("frame"), w.u64(2), w.u64(asU64(-3)); });
        meta.push_back([](ByteWriter& w) { w.str("units"), w.u64(6), w.str("metres"); });
        for (std::int64_t x : {0, 16}) {
            LeafRec leaf{x, 0, 0, {}, {}};
            for (int i = 0; i < 512; ++i) leaf.values[i] = static_cast<float>(i % 7) / 6.0f;
            leaf.mask[0] = 0xff00ff00ff00ff00ull;
            leaf.mask[7] = 1;
            leaves.push_back(leaf);
        }
    }

    Bytes bytes() const
    {
        ByteWriter w;
        w.bytes(tag.data(), tag.size());
        for (double v : matrix) w.f64(v);
        w.bytes(&background, 4);
        w.u64(metaCount);
        for (const auto& m : meta) m(w);
        w.u64(tileCount.value_or(tiles.size()));
        for (const TileRec& t : tiles) {
            w.u64(t.level);
            for (std::int64_t c : {t.x, t.y, t.z}) w.u64(asU64(c));
            w.bytes(&t.value, 4);
            w.u64(t.active);
        }
        w.u64(leafCount.value_or(leaves.size()));
        for (const LeafRec& l : leaves) {
            for (std::int64_t c : {l.x, l.y, l.z}) w.u64(asU64(c));
            for (std::uint64_t m : l.mask) w.u64(m);
            w.bytes(l.values, sizeof l.values);
        }
        return w.buffer();
    }
};

void expectFogRefused(const std::function<void(FogBytes&)>& change, const std::string& why)
{
    FogBytes f;
    change(f);
    SCOPED_TRACE(why);
    expectRefused("FogVolume", f.bytes(), why);
}

TEST(CachedValueDecoding, FogVolumeDecodesTheForgingBaseline)
{
    const FloatGrid::Ptr grid = decodeGrid(FogBytes().bytes());
    EXPECT_EQ(grid->getName(), "density");
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(grid->metaValue<openvdb::Int32>("frame"), -3);
    EXPECT_EQ(grid->metaValue<std::string>("units"), "metres");
    EXPECT_EQ(grid->tree().leafCount(), 2u);
    EXPECT_EQ(grid->tree().activeTileCount(), 2u);
    EXPECT_EQ(grid->tree().getValue(Coord(130, 1, 1)), 0.25f);
    EXPECT_EQ(grid->tree().getValue(Coord(16 + 1, 0, 0)),
              static_cast<float>(64 % 7) / 6.0f);  // offset 64
    EXPECT_EQ(grid->voxelSize(), openvdb::Vec3d(4.0));
    EXPECT_EQ(encodeGrid(*grid), FogBytes().bytes());  // one encoding per grid
}

TEST(CachedValueDecoding, FogVolumeRefusesForgedHeaders)
{
    using F = FogBytes;
    expectFogRefused([](F& f) { f.tag = "CGFOG002"; }, "bad tag");
    expectFogRefused([](F& f) { f.matrix[5] = std::nan(""); }, "the transform is not finite");
    expectFogRefused([](F& f) { f.matrix[3] = 1.0; }, "the transform is not affine");
    expectFogRefused([](F& f) { f.matrix[15] = 2.0; }, "the transform is not affine");
    expectFogRefused([](F& f) { f.matrix[8] = 4.0, f.matrix[10] = 0.0; },
                     "the transform is singular");
    expectFogRefused([](F& f) { f.matrix[4] = 4.0, f.matrix[5] = 1e-9; },
                     "the transform is singular");
    expectFogRefused([](F& f) { f.matrix[0] = 5e-4; }, "voxel axis 0 is");
    expectFogRefused([](F& f) { f.matrix[10] = 1e7; }, "voxel axis 2 is");
    expectFogRefused([](F& f) { f.matrix[13] = 2e9; }, "the translation is out of range");
    expectFogRefused([](F& f) { f.background = 0.5f; }, "background");
    expectFogRefused([](F& f) { f.background = -0.0f; }, "background");
    expectFogRefused([](F& f) { f.metaCount = std::uint64_t{1} << 60; }, "metadata count");
    expectFogRefused([](F& f) { std::swap(f.meta[0], f.meta[1]); }, "out of order or reserved");
    expectFogRefused([](F& f) { f.meta[1] = f.meta[0]; }, "out of order or reserved");
    expectFogRefused([](F& f) { f.meta[0] = [](ByteWriter& w) { w.str(""), w.u64(3), w.u64(1); }; },
                     "metadata name ''");
    expectFogRefused(
        [](F& f) { f.meta[1] = [](ByteWriter& w) { w.str("name"), w.u64(6), w.str("x"); }; },
        "out of order or reserved");
    expectFogRefused(
        [](F& f) { f.meta[1] = [](ByteWriter& w) { w.str("w"), w.u64(7), w.u64(0); }; },
        "unknown kind");
    expectFogRefused(
        [](F& f) { f.meta[1] = [](ByteWriter& w) { w.str("w"), w.u64(1), w.u64(2); }; },
        "bool 2 is above 1");
    expectFogRefused(
        [](F& f) {
            f.meta[1] = [](ByteWriter& w) { w.str("w"), w.u64(2), w.u64(std::uint64_t{1} << 31); };
        },
        "int32 2147483648 is outside");
    expectFogRefused(
        [](F& f) {
            f.meta[0] = [](ByteWriter& w) { w.str("file_compression"), w.u64(3), w.u64(1); };
        },
        "'file_compression' is empty, out of order or reserved");
}

TEST(CachedValueDecoding, FogVolumeRefusesForgedTilesAndLeaves)
{
    using F = FogBytes;
    expectFogRefused([](F& f) { f.tileCount = 1000000; }, "tile count 1000000 runs past the end");
    expectFogRefused([](F& f) { f.tiles[0].level = 0; }, "tile level 0");
    expectFogRefused([](F& f) { f.tiles[2].level = 4; }, "tile level 4");
    expectFogRefused([](F& f) { f.tiles[0].y = 4; }, "tile origin 4 is not a multiple of 8");
    expectFogRefused([](F& f) { f.tiles[1].x = 64; }, "tile origin 64 is not a multiple of 128");
    expectFogRefused([](F& f) { f.tiles[2].z = -(std::int64_t{1} << 30); },
                     "tile coordinate -1073741824 is out of range");
    expectFogRefused([](F& f) { f.tiles[2].z = std::int64_t{1} << 30; },
                     "tile coordinate 1073741824 is out of range");
    expectFogRefused([](F& f) { f.tiles[2].z = std::int64_t{1} << 31; },
                     "coordinate 2147483648 is outside");
    expectFogRefused([](F& f) { f.tiles[0].value = -0.25f; },
                     "tile value -0.250000 is negative or not finite");
    expectFogRefused([](F& f) { f.tiles[0].value = kNaN; }, "negative or not finite");
    expectFogRefused([](F& f) { f.tiles[0].active = 2; }, "tile state 2 is above 1");
    expectFogRefused([](F& f) { f.tiles[0].active = 0, f.tiles[0].value = 0.0f; },
                     "an inactive tile holds the background");
    expectFogRefused([](F& f) { std::swap(f.tiles[0], f.tiles[1]); },
                     "tiles are out of order or repeated");
    expectFogRefused(
        [](F& f) {
            f.tiles[1] = f.tiles[0];
            f.tiles[1].value = 0.75f;
        },
        "tiles are out of order or repeated");
    expectFogRefused([](F& f) { f.tiles[0].x = 4096 + 8; },
                     "a tile lies inside a tile of a higher level");
    expectFogRefused([](F& f) { f.tiles[1].x = 4096 + 128; },
                     "a tile lies inside a tile of a higher level");
    expectFogRefused([](F& f) { f.leafCount = 1000; }, "leaf count 1000 runs past the end");
    expectFogRefused([](F& f) { f.leaves[0].z = 3; }, "leaf origin 3 is not a multiple of 8");
    expectFogRefused([](F& f) { f.leaves[1].x = std::int64_t{1} << 30; },
                     "leaf coordinate 1073741824 is out of range");
    expectFogRefused([](F& f) { std::swap(f.leaves[0], f.leaves[1]); },
                     "leaves are out of order or repeated");
    expectFogRefused([](F& f) { f.leaves[1].x = 0; }, "leaves are out of order or repeated");
    expectFogRefused([](F& f) { f.leaves[1].values[300] = -1e-6f; },
                     "leaf value -0.000001 is negative or not finite");
    expectFogRefused([](F& f) { f.leaves[0].values[0] = kInf; }, "leaf value inf is negative");
    expectFogRefused([](F& f) { f.leaves[0].values[511] = -kNaN; }, "negative or not finite");
    expectFogRefused([](F& f) { f.leaves[1].x = 8; }, "a leaf lies inside a tile");
    expectFogRefused([](F& f) { f.leaves[1].x = 128 + 16; }, "a leaf lies inside a tile");
    expectFogRefused([](F& f) { f.leaves[1].x = 4096 + 512; }, "a leaf lies inside a tile");
}

/// A few bytes of tile must not make megabytes of internal nodes.
TEST(CachedValueDecoding, FogVolumeRefusesTilesThatWouldAllocateAbsurdly)
{
    FogBytes f;
    f.tiles.clear();
    for (std::int64_t i = 1; i <= 1100; ++i) f.tiles.push_back({1, i * 4096, 0, 0, 0.5f, 1});
    expectRefused("FogVolume", f.bytes(), "internal nodes would take");
    f.tiles.resize(20);  // 20 level-2 nodes: fine
    EXPECT_EQ(decodeGrid(f.bytes())->tree().activeTileCount(), 20u);
}

/// What entries written before this format held (OpenVDB's stream) is refused, not parsed.
TEST(CachedValueDecoding, FogVolumeRefusesTheOldStreamFormat)
{
    std::ostringstream stream(std::ios::binary);
    openvdb::io::Stream(stream).write(openvdb::GridCPtrVec{voxelized()});
    ByteWriter out;
    out.str(stream.str());
    expectRefused("FogVolume", out.buffer(), "bad tag");
}

/// Everything a decoded grid must satisfy, checked independently of the decoder.
void expectFogInvariants(const FloatGrid& g)
{
    EXPECT_EQ(g.getName(), "density");
    EXPECT_EQ(g.getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(g.background(), 0.0f);
    ASSERT_TRUE(g.transform().isLinear());
    const openvdb::Mat4d m = g.transform().baseMap()->getAffineMap()->getMat4();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(m(r, c)));
    EXPECT_EQ(m.col(3), openvdb::Vec4d(0, 0, 0, 1));
    EXPECT_NE(m.getMat3().det(), 0.0);
    for (int a = 0; a < 3; ++a) {
        EXPECT_GE(g.voxelSize()[a], 1e-3 * (1 - 1e-9));
        EXPECT_LE(g.voxelSize()[a], 1e6 * (1 + 1e-9));
    }
    std::size_t bad = 0;
    for (auto it = g.tree().cbeginLeaf(); it; ++it) {
        for (openvdb::Index i = 0; i < 512; ++i)
            bad += !(it->getValue(i) >= 0.0f && std::isfinite(it->getValue(i)));
        const Coord o = it->origin();
        bad += std::abs(std::int64_t{o.x()}) >= (1 << 30) ||
               std::abs(std::int64_t{o.y()}) >= (1 << 30) ||
               std::abs(std::int64_t{o.z()}) >= (1 << 30);
    }
    auto tile = g.tree().cbeginValueAll();
    tile.setMaxDepth(tile.getLeafDepth() - 1);
    for (; tile; ++tile) {
        bad += !(*tile >= 0.0f && std::isfinite(*tile));
        openvdb::CoordBBox box;
        tile.getBoundingBox(box);
        for (int a = 0; a < 3; ++a) bad += box.min()[a] <= -(1 << 30) || box.max()[a] >= (1 << 30);
    }
    EXPECT_EQ(bad, 0u);
    // It re-encodes, and that decodes to the same grid: nothing decoded lies outside the format.
    const Bytes again = encodeGrid(g);
    EXPECT_EQ(encodeGrid(*decodeGrid(again)), again);
}

/// Decoding mutated bytes either throws or yields a grid that keeps every invariant.
void decodeMutation(const Bytes& bytes, std::size_t& accepted)
{
    FloatGrid::Ptr grid;
    try {
        grid = decodeGrid(bytes);
    } catch (const std::exception&) {
        return;
    }
    ++accepted;
    expectFogInvariants(*grid);
}

TEST(CachedValueDecoding, FogVolumeSurvivesEveryByteFlippedInTurn)
{
    FogBytes small;
    small.leaves.pop_back();
    const Bytes good = small.bytes();
    std::size_t accepted = 0;
    for (std::size_t i = 0; i < good.size(); ++i) {
        Bytes b = good;
        b[i] ^= 0xff;
        SCOPED_TRACE("byte " + std::to_string(i));
        decodeMutation(b, accepted);
        if (HasFailure()) break;
    }
    EXPECT_GT(accepted, 0u);  // mask bits, metadata values: some flips give another valid grid
}

TEST(CachedValueDecoding, FogVolumeSurvivesRandomOverwrites)
{
    std::mt19937_64 rng(20240613);
    for (const Bytes& good : {FogBytes().bytes(), encodeGrid(*voxelized())}) {
        std::size_t accepted = 0;
        const int trials = good.size() < 10000 ? 3000 : 300;
        for (int trial = 0; trial < trials; ++trial) {
            Bytes b = good;
            const std::size_t at = rng() % (b.size() - 3);
            const std::uint64_t word = rng();
            std::memcpy(&b[at], &word, 4);
            SCOPED_TRACE("trial " + std::to_string(trial) + " at byte " + std::to_string(at));
            decodeMutation(b, accepted);
            if (HasFailure()) return;
        }
        EXPECT_GT(accepted, 0u);
    }
}

}  // namespace

}  // namespace cg
