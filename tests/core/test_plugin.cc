#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Plugin.h"
#include "core/PluginStamp.h"
#include "core/Registry.h"

namespace cg {

namespace fs = std::filesystem;

namespace {

Registry freshRegistry()
{
    Registry r;
    registerCoreDataTypes(r);
    return r;
}

/// Loads `path` expecting an InputError that names the file and contains `text`.
void expectRefused(const fs::path& path, Registry& registry, const std::string& text)
{
    try {
        loadPlugin(path, registry);
        ADD_FAILURE() << "plugin " << path << " was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), path.string());
        const std::string what = e.what();
        EXPECT_NE(what.find(path.string()), std::string::npos) << what;
        EXPECT_NE(what.find(text), std::string::npos) << what;
    }
}

/// A fresh directory under the system temp directory, removed on destruction.
class TempDir {
public:
    TempDir()
    {
        std::string pattern = (fs::temp_directory_path() / "cloudgraph-plugin-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        mPath = pattern;
    }
    ~TempDir()
    {
        std::error_code ec;
        fs::remove_all(mPath, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return mPath; }

private:
    fs::path mPath;
};

void touch(const fs::path& p) { std::ofstream(p) << "x"; }

/// Restores the working directory when the test ends, even on failure.
class CwdGuard {
public:
    CwdGuard() : mSaved(fs::current_path()) {}
    ~CwdGuard() { fs::current_path(mSaved); }
    CwdGuard(const CwdGuard&) = delete;
    CwdGuard& operator=(const CwdGuard&) = delete;

private:
    fs::path mSaved;
};

std::vector<float> cookSampleGain(const NodeDecl& decl, double gain, std::vector<float> values)
{
    ParamSet params(&decl.params);
    params.set("gain", gain);
    EvalContext eval;
    TempDir out;
    CookContext ctx(decl, "gain", params, eval, out.path());
    ctx.setInput("values", std::make_shared<FloatArrayData>(std::move(values)));
    decl.create()->cook(ctx);
    OutputMap outputs = ctx.takeOutputs();
    auto result = std::dynamic_pointer_cast<const FloatArrayData>(outputs["values"]);
    if (!result) throw std::runtime_error("SampleGain set no FloatArray 'values' output");
    return result->values;
}

}  // namespace

TEST(Plugin, SampleRegistersAndCooks)
{
    Registry registry = freshRegistry();
    ASSERT_EQ(registry.findNode("SampleGain"), nullptr);
    loadPlugin(CLOUDGRAPH_SAMPLE_PLUGIN, registry);

    const NodeDecl* decl = registry.findNode("SampleGain");
    ASSERT_NE(decl, nullptr);
    ASSERT_NE(decl->findInput("values"), nullptr);
    ASSERT_NE(decl->findOutput("values"), nullptr);
    const ParamDecl* gain = decl->findParam("gain");
    ASSERT_NE(gain, nullptr);
    EXPECT_EQ(std::get<double>(gain->defaultValue), 2.0);

    const std::vector<float> in = {1.0f, -0.5f, 3.25f, 0.0f, 1e-3f};
    const double g = 2.5;
    const std::vector<float> out = cookSampleGain(*decl, g, in);
    ASSERT_EQ(out.size(), in.size());
    for (std::size_t i = 0; i < in.size(); ++i)
        EXPECT_EQ(out[i], static_cast<float>(in[i] * g)) << "index " << i;
}

TEST(Plugin, BadAbiVersionIsRefused)
{
    Registry registry = freshRegistry();
    expectRefused(CLOUDGRAPH_BAD_ABI_PLUGIN, registry,
                  "plugin ABI version " + std::to_string(CLOUDGRAPH_PLUGIN_ABI_VERSION + 1) +
                      ", this cloudgraph needs " + std::to_string(CLOUDGRAPH_PLUGIN_ABI_VERSION));
    EXPECT_EQ(registry.findNode("SampleGain"), nullptr);
}

TEST(Plugin, MissingEntryPointIsRefused)
{
    Registry registry = freshRegistry();
    expectRefused(CLOUDGRAPH_NO_ENTRY_PLUGIN, registry, "not a CloudGraph plugin: no ABI stamp");
}

TEST(Plugin, AnotherAbiIsRefusedBeforeAnyOfItsCodeRuns)
{
    Registry registry = freshRegistry();
    ::unsetenv("CLOUDGRAPH_TEST_PLUGIN_CONSTRUCTOR_RAN");
    expectRefused(CLOUDGRAPH_CONSTRUCTOR_PLUGIN, registry,
                  "plugin ABI version " + std::to_string(CLOUDGRAPH_PLUGIN_ABI_VERSION + 1));
    EXPECT_EQ(std::getenv("CLOUDGRAPH_TEST_PLUGIN_CONSTRUCTOR_RAN"), nullptr)
        << "the plugin's static constructor ran before its ABI was checked";
}

TEST(Plugin, EntrySymbolsThatAreDataAreRefusedWithoutACrash)
{
    Registry registry = freshRegistry();
    expectRefused(CLOUDGRAPH_DATA_ENTRY_PLUGIN, registry,
                  "entry point 'cloudgraph_plugin_abi_version' is not a function");
}

TEST(Plugin, TheStampReaderRefusesWhatIsNotAWellFormedLibrary)
{
    const std::string image = [] {
        std::ifstream in(CLOUDGRAPH_SAMPLE_PLUGIN, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }();
    auto stampOf = [](const std::string& bytes) {
        const ByteSource read = [&bytes](std::uint64_t offset, void* out, std::size_t size) {
            if (offset > bytes.size() || size > bytes.size() - offset) return false;
            std::memcpy(out, bytes.data() + offset, size);
            return true;
        };
        return readPluginStamp(read, bytes.size());
    };
    EXPECT_EQ(stampOf(image), CLOUDGRAPH_PLUGIN_ABI_VERSION);
    EXPECT_THROW(stampOf(image.substr(0, 40)), std::runtime_error);
    EXPECT_THROW(stampOf(image.substr(0, image.size() / 2)), std::runtime_error);
    EXPECT_THROW(stampOf("#!/bin/sh\necho hi\n" + std::string(64, ' ')), std::runtime_error);
    std::string otherClass = image;
    otherClass[4] = 1;  // EI_CLASS: 32-bit
    EXPECT_THROW(stampOf(otherClass), std::runtime_error);
}

TEST(Plugin, FailedRegistrationIsRefusedAndLeavesRegistryUntouched)
{
    Registry registry = freshRegistry();
    const std::size_t before = registry.nodes().size();
    expectRefused(CLOUDGRAPH_THROWING_PLUGIN, registry, "plugin failed to register: ");
    expectRefused(CLOUDGRAPH_THROWING_PLUGIN, registry, "undocumented");
    // The valid node type registered before the failure is not committed either.
    EXPECT_EQ(registry.findNode("ThrowingFirst"), nullptr);
    EXPECT_EQ(registry.nodes().size(), before);
}

TEST(Plugin, MissingFileIsRefused)
{
    Registry registry = freshRegistry();
    TempDir dir;
    expectRefused(dir.path() / "nope.so", registry, "plugin not found");
}

TEST(Plugin, NonLibraryFileIsRefused)
{
    Registry registry = freshRegistry();
    TempDir dir;
    touch(dir.path() / "junk.so");
    expectRefused(dir.path() / "junk.so", registry, "cannot load plugin: ");
}

TEST(Plugin, LoadingTwiceIsRefusedAndKeepsFirstRegistration)
{
    Registry registry = freshRegistry();
    loadPlugin(CLOUDGRAPH_SAMPLE_PLUGIN, registry);
    expectRefused(CLOUDGRAPH_SAMPLE_PLUGIN, registry, "'SampleGain' is registered twice");

    // The first registration still works: its code was not unloaded.
    const NodeDecl* decl = registry.findNode("SampleGain");
    ASSERT_NE(decl, nullptr);
    EXPECT_EQ(cookSampleGain(*decl, -1.0, {4.0f}), std::vector<float>{-4.0f});
}

TEST(Plugin, SameFileLoadsIntoSeparateRegistries)
{
    Registry a = freshRegistry();
    Registry b = freshRegistry();
    loadPlugin(CLOUDGRAPH_SAMPLE_PLUGIN, a);
    loadPlugin(CLOUDGRAPH_SAMPLE_PLUGIN, b);
    EXPECT_NE(a.findNode("SampleGain"), nullptr);
    EXPECT_NE(b.findNode("SampleGain"), nullptr);
}

TEST(Plugin, SearchPathNullOrEmptyFindsNothing)
{
    EXPECT_TRUE(pluginsFromSearchPath(nullptr).empty());
    EXPECT_TRUE(pluginsFromSearchPath("").empty());
    EXPECT_TRUE(pluginsFromSearchPath(":::").empty());
}

TEST(Plugin, SearchPathIgnoresRelativeEntriesAndWorkingDirectory)
{
    TempDir dir;
    fs::create_directory(dir.path() / "plugins");
    fs::copy_file(CLOUDGRAPH_SAMPLE_PLUGIN, dir.path() / "sample.so");
    fs::copy_file(CLOUDGRAPH_SAMPLE_PLUGIN, dir.path() / "plugins" / "sample.so");

    CwdGuard guard;
    fs::current_path(dir.path());
    EXPECT_TRUE(pluginsFromSearchPath(".").empty());
    EXPECT_TRUE(pluginsFromSearchPath("plugins").empty());
    EXPECT_TRUE(pluginsFromSearchPath("./plugins:plugins/").empty());
    // An absolute entry next to the relative ones still counts.
    const std::string mixed = ".:plugins:" + (dir.path() / "plugins").string();
    EXPECT_EQ(pluginsFromSearchPath(mixed.c_str()),
              std::vector<fs::path>{dir.path() / "plugins" / "sample.so"});
}

TEST(Plugin, SearchPathListsSharedObjectsInOrder)
{
    TempDir dir;
    const fs::path a = dir.path() / "a";
    const fs::path b = dir.path() / "b";
    fs::create_directories(a / "nested");
    fs::create_directories(a / "dir.so");  // a directory, not a plugin
    fs::create_directories(b);
    touch(a / "zeta.so");
    touch(a / "alpha.so");
    touch(a / "notes.txt");
    touch(a / "libx.so.1");
    touch(a / "nested" / "deep.so");  // not searched: the search is not recursive
    touch(b / "middle.so");

    const std::string path = ":" + b.string() + "::" + (dir.path() / "missing").string() +
                             ":relative:" + a.string() + ":";
    const std::vector<fs::path> expected = {b / "middle.so", a / "alpha.so", a / "zeta.so"};
    EXPECT_EQ(pluginsFromSearchPath(path.c_str()), expected);
}

TEST(Plugin, FoundPluginLoads)
{
    TempDir dir;
    fs::copy_file(CLOUDGRAPH_SAMPLE_PLUGIN, dir.path() / "libsample.so");
    const std::string path = dir.path().string();
    const std::vector<fs::path> found = pluginsFromSearchPath(path.c_str());
    ASSERT_EQ(found.size(), 1u);

    Registry registry = freshRegistry();
    loadPlugin(found[0], registry);
    const NodeDecl* decl = registry.findNode("SampleGain");
    ASSERT_NE(decl, nullptr);
    EXPECT_EQ(cookSampleGain(*decl, 2.0, {1.5f, -2.0f}), (std::vector<float>{3.0f, -4.0f}));
}

}  // namespace cg
