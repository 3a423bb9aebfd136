#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/CoreData.h"
#include "core/DiskCache.h"
#include "core/Error.h"
#include "core/Registry.h"
#include "util/SystemMemory.h"

namespace cg {

namespace fs = std::filesystem;

namespace {

/// A fresh directory per test, removed at the end.
class TempDir {
public:
    TempDir()
    {
        static std::atomic<int> counter{0};
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        mPath = fs::temp_directory_path() /
                ("cg-disk-cache-" + std::string(info ? info->name() : "x") + "-" +
                 std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::remove_all(mPath);
        fs::create_directories(mPath);
    }
    ~TempDir()
    {
        std::error_code ec;
        fs::remove_all(mPath, ec);
    }
    const fs::path& path() const { return mPath; }

private:
    fs::path mPath;
};

Key keyOf(std::uint64_t i) { return Key{0x1234567800000000ull + i, ~i * 0x9E3779B97F4A7C15ull}; }

Registry coreRegistry()
{
    Registry r;
    registerCoreDataTypes(r);
    return r;
}

std::vector<unsigned char> readFile(const fs::path& p)
{
    std::vector<unsigned char> bytes(static_cast<std::size_t>(fs::file_size(p)));
    std::ifstream in(p, std::ios::binary);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    return bytes;
}

void writeFile(const fs::path& p, const std::vector<unsigned char>& bytes)
{
    fs::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

void putU64(unsigned char* p, std::uint64_t v)
{
    for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}

OutputMap allCoreTypes()
{
    OutputMap m;
    m["f"] = std::make_shared<FloatData>(-3.25e-7);
    m["i"] = std::make_shared<IntData>(-1234567890123ll);
    std::vector<float> v(1000);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>(i) * 0.5f - 17.0f;
    m["arr"] = std::make_shared<FloatArrayData>(std::move(v));
    m["text"] = std::make_shared<TextData>(std::string("clouds\0and\nrain", 15));
    return m;
}

template <class T>
const T& as(const OutputMap& m, const std::string& port)
{
    const auto it = m.find(port);
    if (it == m.end()) throw std::runtime_error("missing port " + port);
    const auto* p = dynamic_cast<const T*>(it->second.get());
    if (!p) throw std::runtime_error("wrong type on port " + port);
    return *p;
}

void expectAllCoreTypes(const OutputMap& m)
{
    ASSERT_EQ(m.size(), 4u);
    EXPECT_EQ(as<FloatData>(m, "f").value, -3.25e-7);
    EXPECT_EQ(as<IntData>(m, "i").value, -1234567890123ll);
    const auto& arr = as<FloatArrayData>(m, "arr").values;
    ASSERT_EQ(arr.size(), 1000u);
    for (std::size_t i = 0; i < arr.size(); ++i)
        ASSERT_EQ(arr[i], static_cast<float>(i) * 0.5f - 17.0f);
    EXPECT_EQ(as<TextData>(m, "text").value, std::string("clouds\0and\nrain", 15));
}

/// A value whose deserializer reads less than it wrote, or that cannot be stored.
class LooseData final : public Data {
public:
    explicit LooseData(bool storable) : mStorable(storable) {}
    std::string typeName() const override { return "Loose"; }
    std::size_t byteSize() const override { return sizeof(*this); }
    bool serialize(ByteWriter& out) const override
    {
        out.u64(1);
        out.u64(2);
        return mStorable;
    }

private:
    bool mStorable;
};

/// Files under a directory, recursively.
std::vector<fs::path> filesUnder(const fs::path& dir)
{
    std::vector<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out.push_back(e.path());
    return out;
}

}  // namespace

TEST(DiskCache, CreatesLayout)
{
    TempDir dir;
    DiskCache cache(dir.path() / "a" / "b");
    EXPECT_TRUE(fs::is_directory(dir.path() / "a" / "b" / "objects"));
    EXPECT_TRUE(fs::is_directory(dir.path() / "a" / "b" / "tmp"));
    EXPECT_TRUE(fs::is_directory(dir.path() / "a" / "b" / "records"));
    const Key k = keyOf(1);
    const std::string hex = k.hex();
    EXPECT_EQ(cache.entryPath(k),
              dir.path() / "a" / "b" / "objects" / hex.substr(0, 2) / (hex + ".cgc"));
}

TEST(DiskCache, UncreatableRootThrowsInputError)
{
    TempDir dir;
    writeFile(dir.path() / "file", {'x'});
    const fs::path root = dir.path() / "file" / "cache";
    try {
        DiskCache cache(root);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), root.string());
        EXPECT_NE(e.message().find("cannot create cache directory"), std::string::npos);
    }
}

TEST(DiskCache, RoundTripAllCoreTypes)
{
    TempDir dir;
    const Registry registry = coreRegistry();
    const Key k = keyOf(1);
    {
        DiskCache cache(dir.path());
        EXPECT_FALSE(cache.contains(k));
        EXPECT_FALSE(cache.load(k, registry).has_value());
        ASSERT_TRUE(cache.store(k, allCoreTypes()));
        EXPECT_TRUE(cache.contains(k));
    }
    DiskCache again(dir.path());  // a later process, same directory
    const auto loaded = again.load(k, registry);
    ASSERT_TRUE(loaded.has_value());
    expectAllCoreTypes(*loaded);
    EXPECT_FALSE(again.load(keyOf(2), registry).has_value());
    EXPECT_TRUE(filesUnder(dir.path() / "tmp").empty());

    // Storing again overwrites in place.
    OutputMap other;
    other["x"] = std::make_shared<IntData>(7);
    ASSERT_TRUE(again.store(k, other));
    const auto reloaded = again.load(k, registry);
    ASSERT_TRUE(reloaded.has_value());
    ASSERT_EQ(reloaded->size(), 1u);
    EXPECT_EQ(as<IntData>(*reloaded, "x").value, 7);
}

TEST(DiskCache, EmptyOutputsRoundTrip)
{
    TempDir dir;
    DiskCache cache(dir.path());
    ASSERT_TRUE(cache.store(keyOf(3), OutputMap{}));
    const auto loaded = cache.load(keyOf(3), coreRegistry());
    ASSERT_TRUE(loaded.has_value());
    EXPECT_TRUE(loaded->empty());
}

TEST(DiskCache, UnserializableValueStoresNothing)
{
    TempDir dir;
    DiskCache cache(dir.path());
    OutputMap m = allCoreTypes();
    m["loose"] = std::make_shared<LooseData>(false);
    EXPECT_FALSE(cache.store(keyOf(1), m));
    EXPECT_FALSE(cache.contains(keyOf(1)));
    EXPECT_TRUE(filesUnder(dir.path() / "tmp").empty());
}

TEST(DiskCache, EntryFileLayout)
{
    const Key k = keyOf(5);
    std::vector<unsigned char> bytes;
    ASSERT_TRUE(DiskCache::encodeEntry(k, allCoreTypes(), bytes));
    ASSERT_GT(bytes.size(), 56u);
    EXPECT_EQ(std::memcmp(bytes.data(), "CGCACHE1", 8), 0);
    auto u64 = [&](std::size_t at) {
        std::uint64_t v = 0;
        for (int i = 7; i >= 0; --i) v = (v << 8) | bytes[at + static_cast<std::size_t>(i)];
        return v;
    };
    EXPECT_EQ(u64(8), 1u);  // version 1, reserved 0
    EXPECT_EQ(u64(16), k.hi);
    EXPECT_EQ(u64(24), k.lo);
    EXPECT_EQ(u64(32), bytes.size() - 56);
    EXPECT_EQ(u64(40), checksum64(bytes.data() + 56, bytes.size() - 56));
    EXPECT_EQ(u64(48), checksum64(bytes.data(), 48));
    EXPECT_EQ(u64(56), 4u);  // port count
    const auto decoded = DiskCache::decodeEntry(k, bytes.data(), bytes.size(), coreRegistry());
    expectAllCoreTypes(decoded);
}

TEST(DiskCache, TruncatedEntryIsAMissAndRemoved)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key k = keyOf(1);
    ASSERT_TRUE(cache.store(k, allCoreTypes()));
    const auto good = readFile(cache.entryPath(k));
    for (std::size_t size : {good.size() - 1, good.size() / 2, std::size_t(57), std::size_t(55),
                             std::size_t(10), std::size_t(0)}) {
        SCOPED_TRACE("truncated to " + std::to_string(size));
        writeFile(cache.entryPath(k),
                  std::vector<unsigned char>(good.begin(), good.begin() + size));
        EXPECT_FALSE(cache.load(k, registry).has_value());
        EXPECT_FALSE(fs::exists(cache.entryPath(k)));
    }
    // A good entry still loads after all that.
    writeFile(cache.entryPath(k), good);
    ASSERT_TRUE(cache.load(k, registry).has_value());
}

TEST(DiskCache, FlippedByteIsAMissAndRemoved)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key k = keyOf(1);
    ASSERT_TRUE(cache.store(k, allCoreTypes()));
    const auto good = readFile(cache.entryPath(k));
    // Header: magic, version, reserved, key hi/lo, payload length, both checksums.
    // Payload: port count, a name, a type name, a data length, the data, the last byte.
    const std::vector<std::size_t> positions = {0,
                                                7,
                                                8,
                                                13,
                                                16,
                                                31,
                                                32,
                                                39,
                                                40,
                                                47,
                                                48,
                                                55,
                                                56,
                                                64,
                                                72,
                                                80,
                                                good.size() / 2,
                                                good.size() - 1};
    for (std::size_t at : positions) {
        for (unsigned char mask : {0x01, 0x80}) {
            SCOPED_TRACE("flipped byte " + std::to_string(at) + " mask " + std::to_string(mask));
            auto bad = good;
            bad[at] ^= mask;
            writeFile(cache.entryPath(k), bad);
            EXPECT_FALSE(cache.load(k, registry).has_value());
            EXPECT_FALSE(fs::exists(cache.entryPath(k)));
            EXPECT_THROW(DiskCache::decodeEntry(k, bad.data(), bad.size(), registry),
                         std::runtime_error);
        }
    }
}

TEST(DiskCache, EntryUnderAnotherKeyIsAMiss)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key a = keyOf(1), b = keyOf(2);
    ASSERT_TRUE(cache.store(a, allCoreTypes()));
    writeFile(cache.entryPath(b), readFile(cache.entryPath(a)));
    EXPECT_FALSE(cache.load(b, registry).has_value());
    EXPECT_FALSE(fs::exists(cache.entryPath(b)));
    const auto stillGood = cache.load(a, registry);
    ASSERT_TRUE(stillGood.has_value());
    expectAllCoreTypes(*stillGood);
}

TEST(DiskCache, ForeignFileIsAMiss)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key k = keyOf(1);
    std::mt19937 rng(7);
    std::vector<unsigned char> text;
    for (int i = 0; i < 4000; ++i) text.push_back(static_cast<unsigned char>('a' + rng() % 26));
    writeFile(cache.entryPath(k), text);
    EXPECT_FALSE(cache.load(k, registry).has_value());
    EXPECT_FALSE(fs::exists(cache.entryPath(k)));

    // A directory where the entry should be is not an entry either.
    fs::create_directories(cache.entryPath(k));
    EXPECT_FALSE(cache.load(k, registry).has_value());
}

TEST(DiskCache, HugeClaimedLengthsAreRejectedBeforeAllocating)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key k = keyOf(1);
    std::vector<unsigned char> good;
    ASSERT_TRUE(DiskCache::encodeEntry(k, allCoreTypes(), good));

    // Header claims an enormous payload; header checksum made consistent.
    auto bad = good;
    putU64(bad.data() + 32, 1ull << 62);
    putU64(bad.data() + 48, checksum64(bad.data(), 48));
    try {
        DiskCache::decodeEntry(k, bad.data(), bad.size(), registry);
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("at byte 32"), std::string::npos) << e.what();
    }
    writeFile(cache.entryPath(k), bad);
    EXPECT_FALSE(cache.load(k, registry).has_value());
    EXPECT_FALSE(fs::exists(cache.entryPath(k)));

    // Payload claims an enormous port count / array, both checksums made consistent.
    OutputMap one;
    one["arr"] = std::make_shared<FloatArrayData>(std::vector<float>(4, 1.0f));
    std::vector<unsigned char> small;
    ASSERT_TRUE(DiskCache::encodeEntry(k, one, small));
    auto reseal = [](std::vector<unsigned char>& e) {
        putU64(e.data() + 40, checksum64(e.data() + 56, e.size() - 56));
        putU64(e.data() + 48, checksum64(e.data(), 48));
    };
    auto hugeCount = small;
    putU64(hugeCount.data() + 56, ~0ull);
    reseal(hugeCount);
    EXPECT_THROW(DiskCache::decodeEntry(k, hugeCount.data(), hugeCount.size(), registry),
                 std::runtime_error);
    // Layout: count(8) name(8+3) type(8+10) length(8) then the array's own count.
    auto hugeArray = small;
    const std::size_t arrayCountAt = 56 + 8 + 11 + 18 + 8;
    ASSERT_EQ(hugeArray[arrayCountAt], 4u);
    putU64(hugeArray.data() + arrayCountAt, 1ull << 60);
    reseal(hugeArray);
    EXPECT_THROW(DiskCache::decodeEntry(k, hugeArray.data(), hugeArray.size(), registry),
                 std::runtime_error);
    writeFile(cache.entryPath(k), hugeArray);
    EXPECT_FALSE(cache.load(k, registry).has_value());
}

TEST(DiskCache, UnknownTypeOrLooseDeserializerIsAMiss)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Key k = keyOf(1);
    OutputMap m;
    m["loose"] = std::make_shared<LooseData>(true);
    ASSERT_TRUE(cache.store(k, m));
    const auto bytes = readFile(cache.entryPath(k));

    // Unknown type in this registry.
    EXPECT_THROW(DiskCache::decodeEntry(k, bytes.data(), bytes.size(), coreRegistry()),
                 std::runtime_error);
    EXPECT_FALSE(cache.load(k, coreRegistry()).has_value());
    EXPECT_FALSE(fs::exists(cache.entryPath(k)));

    // Known type whose deserializer leaves bytes unread.
    Registry loose = coreRegistry();
    loose.addDataType({"Loose", "reads half of what it wrote", [](ByteReader& in) -> DataPtr {
                           in.u64();
                           return std::make_shared<LooseData>(true);
                       }});
    try {
        DiskCache::decodeEntry(k, bytes.data(), bytes.size(), loose);
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("unread"), std::string::npos) << e.what();
    }
    writeFile(cache.entryPath(k), bytes);
    EXPECT_FALSE(cache.load(k, loose).has_value());
}

namespace {

constexpr std::size_t kBigFloats = 2u * 1024 * 1024;  // 8 MB
constexpr std::uint64_t kKillKeys = 3;

float expectedValue(std::uint64_t key, std::int64_t gen, std::size_t i)
{
    return static_cast<float>((key * 131 + static_cast<std::uint64_t>(gen) * 7 + i) % 65536);
}

/// Deterministic outputs for (key, generation): the generation is stored alongside, so a
/// reader can tell exactly what the whole entry must contain.
OutputMap generation(std::uint64_t key, std::int64_t gen, std::size_t floats)
{
    std::vector<float> v(floats);
    for (std::size_t i = 0; i < floats; ++i) v[i] = expectedValue(key, gen, i);
    OutputMap m;
    m["gen"] = std::make_shared<IntData>(gen);
    m["values"] = std::make_shared<FloatArrayData>(std::move(v));
    m["name"] = std::make_shared<TextData>("key " + std::to_string(key));
    return m;
}

/// Returns an empty string when `m` is exactly generation(key, gen, floats) for its gen.
std::string checkGeneration(const OutputMap& m, std::uint64_t key, std::size_t floats)
{
    if (m.size() != 3) return "wrong port count";
    const std::int64_t gen = as<IntData>(m, "gen").value;
    if (as<TextData>(m, "name").value != "key " + std::to_string(key)) return "wrong name";
    const auto& v = as<FloatArrayData>(m, "values").values;
    if (v.size() != floats) return "wrong array size";
    for (std::size_t i = 0; i < floats; ++i)
        if (v[i] != expectedValue(key, gen, i)) return "wrong value at " + std::to_string(i);
    return {};
}

/// Child body: stores generations firstGen.. (gens of them, or forever when gens < 0) of
/// every key, in turn. With `notify` >= 0 it writes one byte there once the values are
/// built and one after each finished store, so the parent can time its kill.
[[noreturn]] void storeGenerations(const fs::path& root, std::int64_t firstGen, std::int64_t gens,
                                   int notify)
{
    try {
        DiskCache cache(root);
        // Built up front so the kill lands in store() rather than in building values.
        std::vector<OutputMap> built;
        for (std::int64_t gen = firstGen; gen < firstGen + 2; ++gen)
            for (std::uint64_t key = 0; key < kKillKeys; ++key)
                built.push_back(generation(key, gen, kBigFloats));
        const char byte = 1;
        if (notify >= 0 && ::write(notify, &byte, 1) != 1) _exit(4);
        for (std::int64_t n = 0; gens < 0 || n < gens * std::int64_t(kKillKeys); ++n) {
            const std::uint64_t key = static_cast<std::uint64_t>(n) % kKillKeys;
            const auto& outputs = built[static_cast<std::size_t>(n) % built.size()];
            if (!cache.store(keyOf(key), outputs)) _exit(2);
            if (notify >= 0 && ::write(notify, &byte, 1) != 1) _exit(4);
        }
    } catch (...) {
        _exit(3);
    }
    _exit(0);
}

}  // namespace

TEST(DiskCache, KilledWriterNeverLeavesABadEntry)
{
    TempDir dir;
    const Registry registry = coreRegistry();
    std::size_t seenEntries = 0;
    for (int round = 0; round < 10; ++round) {
        SCOPED_TRACE("round " + std::to_string(round));
        int fds[2];
        ASSERT_EQ(::pipe(fds), 0);
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            ::close(fds[0]);
            storeGenerations(dir.path(), round * 1000, -1, fds[1]);
        }
        ::close(fds[1]);
        // Wait until the values are built and 0..3 stores have finished, then kill a few
        // milliseconds later: somewhere inside the next store (encode, write, fsync, rename).
        const int waitFor = 1 + round % 4;
        for (int i = 0; i < waitFor; ++i) {
            char byte;
            ASSERT_EQ(::read(fds[0], &byte, 1), 1);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1 + round * 19 / 9));
        ASSERT_EQ(::kill(child, SIGKILL), 0);
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ::close(fds[0]);
        // Killed mid-run, not failed on its own.
        ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with " << WEXITSTATUS(status);

        DiskCache cache(dir.path());
        for (std::uint64_t key = 0; key < kKillKeys; ++key) {
            // Atomic writes: any file under objects/ is a whole entry, never a torn one
            // (load() would hide a torn one as a miss, so look at the bytes directly).
            if (fs::exists(cache.entryPath(keyOf(key)))) {
                const auto bytes = readFile(cache.entryPath(keyOf(key)));
                EXPECT_NO_THROW(
                    DiskCache::decodeEntry(keyOf(key), bytes.data(), bytes.size(), registry))
                    << "torn entry for key " << key << " (" << bytes.size() << " bytes)";
            }
            const auto loaded = cache.load(keyOf(key), registry);
            if (!loaded) continue;
            ++seenEntries;
            EXPECT_EQ(checkGeneration(*loaded, key, kBigFloats), "") << "key " << key;
            // A loaded entry is a whole, undamaged file, so it stays.
            EXPECT_TRUE(cache.contains(keyOf(key)));
        }
        // Only finished entries are under objects/; half-written ones stay in tmp/.
        for (const fs::path& p : filesUnder(dir.path() / "objects")) {
            EXPECT_EQ(p.extension(), ".cgc") << p;
            EXPECT_EQ(p.parent_path().parent_path(), dir.path() / "objects") << p;
        }
    }
    // Rounds 2..9 waited for at least one finished store before killing.
    EXPECT_GE(seenEntries, 8u);

    // Temp files (partial or whole) are never read as entries, even with objects/ empty.
    const std::size_t leftovers = filesUnder(dir.path() / "tmp").size();
    {
        DiskCache cache(dir.path());
        std::vector<unsigned char> whole;
        ASSERT_TRUE(DiskCache::encodeEntry(keyOf(0), generation(0, 1, 16), whole));
        writeFile(dir.path() / "tmp" / (keyOf(0).hex() + ".cgc"), whole);
        writeFile(dir.path() / "tmp" / "1-2-3.tmp", whole);
        fs::remove_all(dir.path() / "objects");
        for (std::uint64_t key = 0; key < kKillKeys; ++key) {
            EXPECT_FALSE(cache.contains(keyOf(key)));
            EXPECT_FALSE(cache.load(keyOf(key), registry).has_value());
        }
    }

    // A writer left to finish stores every key; all load with the expected generation.
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) storeGenerations(dir.path(), 99000, 2, -1);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    ASSERT_EQ(WEXITSTATUS(status), 0);
    DiskCache cache(dir.path());
    for (std::uint64_t key = 0; key < kKillKeys; ++key) {
        const auto loaded = cache.load(keyOf(key), registry);
        ASSERT_TRUE(loaded.has_value()) << "key " << key;
        EXPECT_EQ(checkGeneration(*loaded, key, kBigFloats), "");
        EXPECT_EQ(as<IntData>(*loaded, "gen").value, 99001);
    }
    std::cout << "[          ] entries checked after kills: " << seenEntries
              << ", temp files left by killed writers: " << leftovers << "\n";
}

TEST(DiskCache, TwoProcessesStoringSameKeysBothSucceed)
{
    TempDir dir;
    constexpr std::uint64_t keys = 8;
    constexpr std::size_t floats = 64 * 1024;
    pid_t children[2];
    for (pid_t& child : children) {
        child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            try {
                DiskCache cache(dir.path());
                for (int rep = 0; rep < 10; ++rep)
                    for (std::uint64_t key = 0; key < keys; ++key)
                        if (!cache.store(keyOf(key), generation(key, 5, floats))) _exit(2);
            } catch (...) {
                _exit(3);
            }
            _exit(0);
        }
    }
    for (pid_t child : children) {
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFEXITED(status));
        EXPECT_EQ(WEXITSTATUS(status), 0);
    }
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    for (std::uint64_t key = 0; key < keys; ++key) {
        const auto loaded = cache.load(keyOf(key), registry);
        ASSERT_TRUE(loaded.has_value()) << "key " << key;
        EXPECT_EQ(checkGeneration(*loaded, key, floats), "");
        EXPECT_EQ(as<IntData>(*loaded, "gen").value, 5);
    }
    EXPECT_TRUE(filesUnder(dir.path() / "tmp").empty());
}

TEST(DiskCache, RecordsRoundTrip)
{
    TempDir dir;
    const nlohmann::json record = {{"node", "noise"}, {"frame", 12}, {"why", {"param", "seed"}}};
    {
        DiskCache cache(dir.path());
        EXPECT_FALSE(cache.loadRecord("run").has_value());
        cache.storeRecord("run", record);
        cache.storeRecord("a/b c", {{"x", 1}});
    }
    DiskCache cache(dir.path());
    const auto loaded = cache.loadRecord("run");
    ASSERT_TRUE(loaded.has_value());
    EXPECT_EQ(*loaded, record);
    // Names are sanitized, so a record never escapes records/.
    EXPECT_TRUE(fs::exists(dir.path() / "records" / "a_b_c.json"));
    ASSERT_TRUE(cache.loadRecord("a/b c").has_value());
    EXPECT_EQ((*cache.loadRecord("a/b c"))["x"], 1);
    cache.storeRecord("run", {{"replaced", true}});
    EXPECT_EQ((*cache.loadRecord("run"))["replaced"], true);
    EXPECT_TRUE(filesUnder(dir.path() / "tmp").empty());
}

TEST(DiskCache, CorruptedRecordIsNullopt)
{
    TempDir dir;
    DiskCache cache(dir.path());
    cache.storeRecord("run", {{"a", 1}});
    const fs::path p = dir.path() / "records" / "run.json";
    ASSERT_TRUE(fs::exists(p));
    auto bytes = readFile(p);
    bytes.resize(bytes.size() / 2);
    writeFile(p, bytes);
    EXPECT_FALSE(cache.loadRecord("run").has_value());
    writeFile(p, {'{', 'n', 'o', 't', ' ', 'j', 's', 'o', 'n'});
    EXPECT_FALSE(cache.loadRecord("run").has_value());
}

}  // namespace cg

namespace cg {

namespace {

std::vector<PortDecl> declaredOutputs()
{
    return {{"arr", "FloatArray", ""}, {"f", "Float", ""}, {"i", "Int", ""}, {"text", "Text", ""}};
}

}  // namespace

TEST(DiskCache, AForgedEntryWithARenamedPortOrAnotherTypeIsRecookedNotAnError)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const std::vector<PortDecl> outputs = declaredOutputs();
    const Key k = keyOf(7);
    ASSERT_TRUE(cache.store(k, allCoreTypes()));
    ASSERT_TRUE(cache.load(k, registry, &outputs).has_value());

    OutputMap renamed = allCoreTypes();
    renamed["g"] = renamed["f"];
    renamed.erase("f");
    OutputMap retyped = allCoreTypes();
    retyped["f"] = std::make_shared<IntData>(1);
    OutputMap extra = allCoreTypes();
    extra["z"] = std::make_shared<IntData>(1);
    for (const OutputMap& forged : {renamed, retyped, extra}) {
        std::vector<unsigned char> entry;
        ASSERT_TRUE(DiskCache::encodeEntry(k, forged, entry));
        writeFile(cache.entryPath(k), entry);
        EXPECT_FALSE(cache.load(k, registry, &outputs).has_value());
        EXPECT_FALSE(fs::exists(cache.entryPath(k))) << "a forged entry stays and fails again";
    }
}

TEST(DiskCache, AHugeDamagedEntryIsRefusedByItsHeaderWithoutReadingIt)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key k = keyOf(8);
    // A sparse 12 GiB file: reading it would take minutes and all the memory.
    const fs::path path = cache.entryPath(k);
    fs::create_directories(path.parent_path());
    {
        std::ofstream(path, std::ios::binary) << "not an entry";
    }
    fs::resize_file(path, 12ull << 30);
    EXPECT_FALSE(cache.load(k, registry).has_value());
    EXPECT_FALSE(fs::exists(path));

    // A valid header claiming a payload larger than the memory there is: a miss that keeps
    // the entry (it may be valid; this machine cannot load it now).
    std::vector<unsigned char> entry;
    ASSERT_TRUE(DiskCache::encodeEntry(k, allCoreTypes(), entry));
    const std::uint64_t huge = 60ull << 30;
    if (util::availableMemoryBytes() / 2 > huge) GTEST_SKIP() << "this machine could load it";
    putU64(entry.data() + 32, huge);
    putU64(entry.data() + 48, checksum64(entry.data(), 48));
    writeFile(path, std::vector<unsigned char>(entry.begin(), entry.begin() + 56));
    fs::resize_file(path, 56 + huge);
    EXPECT_FALSE(cache.load(k, registry).has_value());
    EXPECT_TRUE(fs::exists(path));
}

/// A value whose rebuilding runs out of memory, as a large valid entry may.
class HeavyData final : public Data {
public:
    std::string typeName() const override { return "Heavy"; }
    std::size_t byteSize() const override { return sizeof(*this); }
    bool serialize(ByteWriter& out) const override
    {
        out.u64(1);
        return true;
    }
};

TEST(DiskCache, RunningOutOfMemoryIsAMissThatKeepsTheEntry)
{
    TempDir dir;
    DiskCache cache(dir.path());
    Registry registry = coreRegistry();
    registry.addDataType({"Heavy", "", [](ByteReader&) -> DataPtr { throw std::bad_alloc(); }});
    const Key k = keyOf(9);
    OutputMap heavy;
    heavy["h"] = std::make_shared<HeavyData>();
    ASSERT_TRUE(cache.store(k, heavy));
    EXPECT_FALSE(cache.load(k, registry).has_value());
    EXPECT_TRUE(fs::exists(cache.entryPath(k))) << "a valid entry was deleted";
}

TEST(DiskCache, AFifoInPlaceOfAnEntryNeitherHangsNorCrashes)
{
    TempDir dir;
    DiskCache cache(dir.path());
    const Registry registry = coreRegistry();
    const Key k = keyOf(10);
    const fs::path path = cache.entryPath(k);
    fs::create_directories(path.parent_path());
    ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
    EXPECT_FALSE(cache.load(k, registry).has_value());
    EXPECT_FALSE(fs::exists(path));
    ASSERT_TRUE(cache.store(k, allCoreTypes()));
    EXPECT_TRUE(cache.load(k, registry).has_value());
}

}  // namespace cg
