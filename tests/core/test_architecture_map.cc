// docs/architecture.md's table of where things live names every source file under algo/, so a
// newcomer finds each file's job there.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace cg {

TEST(ArchitectureMap, NamesEverySourceFileUnderAlgo)
{
    const std::filesystem::path root(CLOUDGRAPH_SOURCE_DIR);
    std::ifstream in(root / "docs" / "architecture.md");
    ASSERT_TRUE(in) << "docs/architecture.md is missing";
    std::stringstream text;
    text << in.rdbuf();
    const std::string doc = text.str();
    std::set<std::string> missing;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / "algo")) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".h" && ext != ".cc") continue;
        // A file is named by its stem (Voxelize names Voxelize.h and Voxelize.cc) or, for a
        // header alone, by its name (GroundGrid.h).
        const std::string stem = entry.path().stem().string();
        if (doc.find("`" + stem + "`") == std::string::npos &&
            doc.find("`" + stem + ".h`") == std::string::npos)
            missing.insert(std::filesystem::relative(entry.path(), root).string());
    }
    EXPECT_TRUE(missing.empty()) << "docs/architecture.md does not name " << [&] {
        std::string s;
        for (const auto& m : missing) s += m + " ";
        return s;
    }() << "(add each to the table 'Where the paper lives')";
}

}  // namespace cg
