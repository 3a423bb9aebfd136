// GraphDocument, what `cloudgraph serve` and the Python module's Graph edit through: Save
// writes through a symbolic link and keeps the file's mode and owner, and a cook that fails
// before it starts (a cache that cannot be made) does not refuse every later cook.

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/GraphDocument.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"
#include "support/TestUtil.h"

namespace cg {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const char* kGraph = R"({
  "cloudgraph": 1,
  "frames": {"start": 0, "end": 2},
  "nodes": {
    "field": {"type": "RandomField", "params": {"width": 4, "height": 2, "seed": 3}}
  }
})";

class GraphDocumentTest : public ::testing::Test {
protected:
    void SetUp() override { registerBuiltinNodes(registry); }
    std::unique_ptr<GraphDocument> load(const fs::path& path)
    {
        return GraphDocument::load(path, registry);
    }
    Registry registry;
};

struct stat statOf(const fs::path& path)
{
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st;
}

}  // namespace

TEST_F(GraphDocumentTest, SaveWritesThroughASymbolicLinkToItsTarget)
{
    TempDir dir;
    fs::create_directories(dir / "versions");
    test::writeFile(dir / "versions/v3.json", kGraph);
    fs::create_symlink("versions/v3.json", dir / "current.json");   // relative, as ln -s makes
    fs::create_symlink(dir / "current.json", dir / "latest.json");  // a link to a link

    for (const std::string name : {"current.json", "latest.json"}) {
        auto doc = load(dir / name);
        const int width = name == "current.json" ? 5 : 6;
        doc->setParam("field", "width", width);
        doc->save(dir / name);
        EXPECT_TRUE(fs::is_symlink(dir / "current.json")) << "the link was replaced by a file";
        EXPECT_TRUE(fs::is_symlink(dir / name)) << name;
        EXPECT_EQ(fs::read_symlink(dir / "current.json"), "versions/v3.json");
        const std::string saved = test::readFile(dir / "versions/v3.json");
        EXPECT_NE(saved.find("\"width\": " + std::to_string(width)), std::string::npos) << saved;
    }
    // Nothing else was left in either directory (no temporaries).
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir.path())) files += !e.is_directory();
    EXPECT_EQ(files, 3u);
}

TEST_F(GraphDocumentTest, SaveKeepsTheFilesModeAndOwner)
{
    TempDir dir;
    const fs::path file = dir / "g.json";
    for (const mode_t mode : {0600, 0640, 0664}) {
        test::writeFile(file, kGraph);
        ASSERT_EQ(::chmod(file.c_str(), mode), 0);
        auto doc = load(file);
        doc->setParam("field", "width", 7);
        doc->save(file);
        EXPECT_EQ(statOf(file).st_mode & 07777, mode) << std::oct << mode;
    }
    // The mode of a link's target, not of the link.
    test::writeFile(dir / "target.json", kGraph);
    ASSERT_EQ(::chmod((dir / "target.json").c_str(), 0600), 0);
    fs::create_symlink("target.json", dir / "link.json");
    load(dir / "link.json")->save(dir / "link.json");
    EXPECT_EQ(statOf(dir / "target.json").st_mode & 07777, 0600u);

    // Only root may give a file away: as root, a graph of another user stays theirs.
    if (::geteuid() != 0) GTEST_SKIP() << "the owner needs root to test";
    ASSERT_EQ(::chown(file.c_str(), 65534, 65534), 0);
    load(file)->save(file);
    EXPECT_EQ(statOf(file).st_uid, 65534u);
    EXPECT_EQ(statOf(file).st_gid, 65534u);
}

TEST_F(GraphDocumentTest, ACacheThatCannotBeMadeDoesNotWedgeTheNextCook)
{
    TempDir dir;
    test::writeFile(dir / "g.json", kGraph);
    test::writeFile(dir / "a-file", "not a directory");
    auto doc = load(dir / "g.json");
    const Graph graph = doc->completeGraph();
    const std::string out = (dir / "out").string();

    for (int attempt = 0; attempt < 2; ++attempt) {
        try {
            doc->cook(graph, "field", "values", 0, (dir / "a-file/cache").string(), out);
            ADD_FAILURE() << "a cache under a file was accepted";
        } catch (const CookInProgress& e) {
            ADD_FAILURE() << "attempt " << attempt << ": " << e.what();
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("a-file"), std::string::npos) << e.what();
        }
        EXPECT_FALSE(doc->progress().cooking);
    }
    // A good cache afterwards cooks.
    EXPECT_NE(doc->cook(graph, "field", "values", 0, (dir / "cache").string(), out), nullptr);
    EXPECT_FALSE(doc->progress().cooking);
    EXPECT_TRUE(fs::is_directory(dir / "cache/objects"));
}

}  // namespace cg
