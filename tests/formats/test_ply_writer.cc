// Binary PLY writer, read back by a minimal independent PLY reader.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "formats/CloudPly.h"
#include "formats/PlyWriter.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

/// What a generic PLY reader sees: header lines, the vertex element's properties and its
/// records, every property widened to double (float and int are both exact in a double).
struct PlyFile {
    std::vector<std::string> headerLines;
    std::vector<std::pair<std::string, std::string>> properties;  ///< (type, name)
    std::size_t count = 0;
    std::vector<std::vector<double>> records;

    double value(std::size_t record, const std::string& name) const
    {
        for (std::size_t p = 0; p < properties.size(); ++p)
            if (properties[p].second == name) return records.at(record).at(p);
        throw std::runtime_error("no property " + name);
    }
};

std::uint32_t leU32(const unsigned char* b)
{
    return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
           static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

/// Reads a binary_little_endian PLY with one vertex element of float, int, uint and uchar
/// properties.
PlyFile readPly(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path.string());
    PlyFile ply;
    std::string line;
    while (std::getline(in, line)) {
        ply.headerLines.push_back(line);
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "element") {
            std::string name;
            words >> name >> ply.count;
            if (name != "vertex") throw std::runtime_error("unexpected element " + name);
        } else if (keyword == "property") {
            std::string type, name;
            words >> type >> name;
            if (type != "float" && type != "int" && type != "uint" && type != "uchar")
                throw std::runtime_error("type " + type);
            ply.properties.emplace_back(type, name);
        } else if (keyword == "end_header") {
            break;
        }
    }
    if (ply.headerLines.empty() || ply.headerLines.back() != "end_header")
        throw std::runtime_error("no end_header");

    std::size_t recordBytes = 0;
    for (const auto& property : ply.properties) recordBytes += property.first == "uchar" ? 1 : 4;
    std::vector<unsigned char> record(recordBytes);
    for (std::size_t i = 0; i < ply.count; ++i) {
        if (!in.read(reinterpret_cast<char*>(record.data()),
                     static_cast<std::streamsize>(recordBytes)))
            throw std::runtime_error("truncated at record " + std::to_string(i));
        std::vector<double> values;
        const unsigned char* at = record.data();
        for (const auto& property : ply.properties) {
            if (property.first == "uchar") {
                values.push_back(*at++);
                continue;
            }
            const std::uint32_t bits = leU32(at);
            at += 4;
            if (property.first == "float") {
                float f;
                std::memcpy(&f, &bits, sizeof f);
                values.push_back(f);
            } else if (property.first == "uint") {
                values.push_back(bits);
            } else {
                values.push_back(static_cast<std::int32_t>(bits));
            }
        }
        ply.records.push_back(std::move(values));
    }
    if (in.peek() != std::char_traits<char>::eof()) throw std::runtime_error("trailing bytes");
    return ply;
}

struct Arrays {
    std::vector<float> x, y, z, vx, vy, vz, t;
    std::vector<std::uint32_t> id, home;
    std::vector<std::int32_t> state;

    formats::PlyParticleView view(bool withState) const
    {
        formats::PlyParticleView v;
        v.count = x.size();
        v.x = x.data();
        v.y = y.data();
        v.z = z.data();
        v.vx = vx.data();
        v.vy = vy.data();
        v.vz = vz.data();
        v.temperature = t.data();
        v.id = id.data();
        v.state = withState ? state.data() : nullptr;
        v.homeCell = home.data();
        return v;
    }
};

Arrays sample(std::size_t n)
{
    Arrays a;
    for (std::size_t i = 0; i < n; ++i) {
        const auto f = static_cast<float>(i);
        a.x.push_back(f * 0.5f + 0.125f);
        a.y.push_back(-f * 3.25f);
        a.z.push_back(1e3f + f / 7.0f);
        a.vx.push_back(4.0f + f * 0.25f);
        a.vy.push_back(-f * 2e-3f);
        a.vz.push_back(i % 3 == 0 ? -0.0f : f * 1e-3f);
        a.t.push_back(30.0f - f * 0.01f);
        a.id.push_back(static_cast<std::uint32_t>(i));
        a.home.push_back(static_cast<std::uint32_t>(n - i));
        a.state.push_back(i % 2 == 0 ? 1 : 0);
    }
    // Extremes a reader must get bit for bit.
    if (n > 2) {
        a.x[1] = std::numeric_limits<float>::denorm_min();
        a.z[2] = std::numeric_limits<float>::max();
        a.id[2] = static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max());
    }
    return a;
}

}  // namespace

TEST(PlyWriter, HeaderIsExactlyTheDocumentedOne)
{
    test::TempDir dir;
    const Arrays a = sample(3);
    formats::writeParticlesPly(dir / "a.ply", a.view(true), "frame 4\nsecond line");
    const std::string text = test::readFile(dir / "a.ply");
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment CloudGraph frame 4 second line\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property float vx\nproperty float vy\n"
        "property float vz\nproperty float temperature\nproperty int id\nproperty int state\n"
        "property int home_cell\nend_header\n";
    ASSERT_EQ(text.substr(0, header.size()), header);
    EXPECT_EQ(text.size(), header.size() + 3 * formats::kPlyRecordBytes);
}

TEST(PlyWriter, ReaderGetsBackEveryValue)
{
    test::TempDir dir;
    // More than one write chunk (32768 records), so chunk boundaries are covered.
    const Arrays a = sample(70001);
    formats::writeParticlesPly(dir / "p.ply", a.view(true), "test");
    const PlyFile ply = readPly(dir / "p.ply");

    EXPECT_EQ(ply.headerLines.at(0), "ply");
    EXPECT_EQ(ply.headerLines.at(1), "format binary_little_endian 1.0");
    EXPECT_EQ(ply.headerLines.at(2), "comment CloudGraph test");
    const std::vector<std::pair<std::string, std::string>> props = {
        {"float", "x"},   {"float", "y"},      {"float", "z"},           {"float", "vx"},
        {"float", "vy"},  {"float", "vz"},     {"float", "temperature"}, {"int", "id"},
        {"int", "state"}, {"int", "home_cell"}};
    EXPECT_EQ(ply.properties, props);
    ASSERT_EQ(ply.count, a.x.size());

    for (std::size_t i = 0; i < ply.count; ++i) {
        ASSERT_EQ(ply.value(i, "x"), a.x[i]) << i;
        ASSERT_EQ(ply.value(i, "y"), a.y[i]) << i;
        ASSERT_EQ(ply.value(i, "z"), a.z[i]) << i;
        ASSERT_EQ(ply.value(i, "vx"), a.vx[i]) << i;
        ASSERT_EQ(ply.value(i, "vy"), a.vy[i]) << i;
        ASSERT_EQ(ply.value(i, "vz"), a.vz[i]) << i;
        ASSERT_EQ(ply.value(i, "temperature"), a.t[i]) << i;
        ASSERT_EQ(ply.value(i, "id"), a.id[i]) << i;
        ASSERT_EQ(ply.value(i, "state"), a.state[i]) << i;
        ASSERT_EQ(ply.value(i, "home_cell"), a.home[i]) << i;
    }
    EXPECT_TRUE(std::signbit(ply.value(0, "vz")));  // -0 survives
}

TEST(PlyWriter, StateIsZeroWithoutCondensationAndEmptyIsValid)
{
    test::TempDir dir;
    const Arrays a = sample(5);
    formats::writeParticlesPly(dir / "s.ply", a.view(false));
    const PlyFile ply = readPly(dir / "s.ply");
    EXPECT_EQ(ply.headerLines.at(2), "comment CloudGraph");
    ASSERT_EQ(ply.count, 5u);
    for (std::size_t i = 0; i < ply.count; ++i) EXPECT_EQ(ply.value(i, "state"), 0.0);

    formats::writeParticlesPly(dir / "e.ply", formats::PlyParticleView{});
    EXPECT_EQ(readPly(dir / "e.ply").count, 0u);
}

TEST(PlyWriter, ErrorsNameTheFile)
{
    test::TempDir dir;
    const Arrays a = sample(3);
    const auto bad = dir / "missing" / "dir" / "x.ply";
    try {
        formats::writeParticlesPly(bad, a.view(true));
        FAIL() << "expected a throw";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
    }

    Arrays big = sample(3);
    big.id[1] = 0x80000000u;  // does not fit a PLY int
    EXPECT_THROW(formats::writeParticlesPly(dir / "big.ply", big.view(true)), std::range_error);

    formats::PlyParticleView missing = a.view(true);
    missing.temperature = nullptr;
    EXPECT_THROW(formats::writeParticlesPly(dir / "m.ply", missing), std::invalid_argument);
}

TEST(PlyWriter, CloudParticlesCarryLevelAndSourceInA17ByteRecord)
{
    test::TempDir dir;
    const std::vector<float> xyz = {1.5f, -2.0f, 300.25f, 4.0f, 5.0f, 6.0f};
    const std::vector<std::uint8_t> levels = {1, 5};
    const std::vector<std::uint32_t> sources = {7, 0xFFFFFFF0u};
    formats::writeCloudPly(dir / "c.ply", 2, xyz.data(), levels.data(), sources.data(), "frame 3");
    const PlyFile ply = readPly(dir / "c.ply");
    EXPECT_EQ(ply.headerLines.at(2), "comment CloudGraph frame 3");
    ASSERT_EQ(ply.count, 2u);
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"float", "x"}, {"float", "y"}, {"float", "z"}, {"uchar", "level"}, {"uint", "source"}};
    EXPECT_EQ(ply.properties, expected);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(ply.value(i, "x"), xyz[3 * i]);
        EXPECT_EQ(ply.value(i, "y"), xyz[3 * i + 1]);
        EXPECT_EQ(ply.value(i, "z"), xyz[3 * i + 2]);
        EXPECT_EQ(ply.value(i, "level"), levels[i]);
        EXPECT_EQ(ply.value(i, "source"), sources[i]);
    }
    formats::writeCloudPly(dir / "e.ply", 0, nullptr, nullptr, nullptr);
    EXPECT_EQ(readPly(dir / "e.ply").count, 0u);
}

// With motion, each record goes on with the velocity and the stable id, written from chunks
// in any order at their places.
TEST(PlyWriter, CloudParticlesWithMotionCarryVelocityAndIdInA33ByteRecord)
{
    test::TempDir dir;
    const std::vector<float> xyz = {1.5f, -2.0f, 300.25f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f};
    const std::vector<float> v = {0.5f, -1.0f, 8.25f, 0.0f, 2.0f, -3.0f, 1e-3f, 0.0f, 7.0f};
    const std::vector<std::uint8_t> levels = {1, 2, 3};
    const std::vector<std::uint32_t> sources = {0, 4, 9};
    const std::vector<std::uint32_t> ids = {17, 3, 0xFFFFFFFEu};
    {
        formats::CloudPlyChunkWriter w(dir / "m.ply", {{2, 1}, {0, 2}}, "frame 4", true);
        w.write(2, 1, &xyz[6], &levels[2], &sources[2], &v[6], &ids[2]);
        w.write(0, 2, xyz.data(), levels.data(), sources.data(), v.data(), ids.data());
        w.close();
    }
    const PlyFile ply = readPly(dir / "m.ply");
    ASSERT_EQ(ply.count, 3u);
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"float", "x"},  {"float", "y"},  {"float", "z"},  {"uchar", "level"}, {"uint", "source"},
        {"float", "vx"}, {"float", "vy"}, {"float", "vz"}, {"uint", "id"}};
    EXPECT_EQ(ply.properties, expected);
    const std::string bytes = test::readFile(dir / "m.ply");
    EXPECT_EQ(bytes.size(), bytes.find("end_header\n") + 11 + 3 * 33);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(ply.value(i, "z"), xyz[3 * i + 2]);
        EXPECT_EQ(ply.value(i, "vx"), v[3 * i]);
        EXPECT_EQ(ply.value(i, "vy"), v[3 * i + 1]);
        EXPECT_EQ(ply.value(i, "vz"), v[3 * i + 2]);
        EXPECT_EQ(ply.value(i, "id"), ids[i]);
    }
}

}  // namespace cg
