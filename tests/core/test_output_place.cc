// Output files stay beneath the output directory: util::makeOutputPlace and
// CookContext::outputPath refuse a symbolic link inside --out that leads out of it, create
// nothing outside it, and still follow links that stay inside.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/Error.h"
#include "core/Node.h"
#include "support/TestUtil.h"
#include "util/Beneath.h"

namespace cg {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

bool isEmptyDirectory(const fs::path& dir) { return fs::is_empty(dir); }

}  // namespace

TEST(OutputPlace, DirectoriesAreMadeBeneathTheRootAndLinksOutOfItAreRefused)
{
    TempDir dir;
    const fs::path out = dir / "out";
    fs::create_directories(dir / "elsewhere");
    fs::create_directories(out / "inside");
    fs::create_symlink(dir / "elsewhere", out / "demo");   // absolute, out of --out
    fs::create_symlink("../elsewhere", out / "up");        // relative, out of --out
    fs::create_symlink("inside", out / "relative");        // stays inside
    fs::create_symlink(out / "inside", out / "absolute");  // absolute, but inside
    test::writeFile(out / "a-file", "x");

    EXPECT_EQ(util::makeOutputPlace(out, "a/b/c/frame.0001.png"), "");
    EXPECT_TRUE(fs::is_directory(out / "a/b/c"));
    EXPECT_EQ(util::makeOutputPlace(dir / "new-out", "x.png"), "");
    EXPECT_TRUE(fs::is_directory(dir / "new-out"));

    for (const std::string file : {"demo/x.png", "demo/deeper/x.png", "up/x.png"}) {
        const std::string problem = util::makeOutputPlace(out, file);
        EXPECT_NE(problem.find("leads outside the output directory"), std::string::npos)
            << file << ": " << problem;
        EXPECT_NE(problem.find(file.substr(0, file.find('/'))), std::string::npos) << problem;
        EXPECT_EQ(util::outputPlaceProblem(out, file), problem);
    }
    EXPECT_TRUE(isEmptyDirectory(dir / "elsewhere")) << "a directory was made outside --out";

    EXPECT_EQ(util::makeOutputPlace(out, "relative/sub/x.png"), "");
    EXPECT_EQ(util::makeOutputPlace(out, "absolute/sub2/x.png"), "");
    EXPECT_TRUE(fs::is_directory(out / "inside/sub"));
    EXPECT_TRUE(fs::is_directory(out / "inside/sub2"));

    EXPECT_NE(util::makeOutputPlace(out, "a-file/x.png").find("'a-file' is not a directory"),
              std::string::npos);
    EXPECT_NE(util::makeOutputPlace(out, "a/b").find("'a/b' is a directory"), std::string::npos);

    // The check alone creates nothing.
    EXPECT_EQ(util::outputPlaceProblem(out, "p/q/x.png"), "");
    EXPECT_FALSE(fs::exists(out / "p"));
    EXPECT_EQ(util::outputPlaceProblem(dir / "missing", "p/x.png"), "");
    EXPECT_FALSE(fs::exists(dir / "missing"));
}

TEST(OutputPlace, AWritersPathThroughALinkOutOfOutIsAnInputErrorNamingTheParameter)
{
    TempDir dir;
    const fs::path out = dir / "out";
    fs::create_directories(dir / "elsewhere");
    fs::create_directories(out);
    fs::create_symlink(dir / "elsewhere", out / "demo");

    NodeDecl decl;
    decl.type = "Writer";
    ParamDecl file;
    file.name = "file";
    file.type = ParamType::String;
    file.role = ParamRole::OutputPath;
    file.defaultValue = std::string("demo/sub/frame.####.txt");
    decl.params = {file};
    const ParamSet params(&decl.params);
    EvalContext eval;
    eval.frame = 3;

    const CookContext confined(decl, "w", params, eval, out);
    try {
        confined.outputPath("file");
        ADD_FAILURE() << "a path through out/demo was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "w/params/file");
        EXPECT_NE(e.message().find((out / "demo/sub/frame.0003.txt").string()), std::string::npos)
            << e.message();
        EXPECT_NE(e.message().find("--allow-outside-out"), std::string::npos) << e.message();
    }
    EXPECT_TRUE(isEmptyDirectory(dir / "elsewhere"));

    // The user may let outputs leave --out: then the link is followed.
    eval.allowOutsideOut = true;
    const CookContext allowed(decl, "w", params, eval, out);
    EXPECT_EQ(allowed.outputPath("file"), out / "demo/sub/frame.0003.txt");
    EXPECT_TRUE(fs::is_directory(dir / "elsewhere/sub"));
}

}  // namespace cg
