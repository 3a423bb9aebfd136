// WrittenFiles: a writer's record verifies only while every file it names holds the bytes
// it wrote, in the same output directory; a damaged or forged record is a miss, never a
// crash and never a skipped write.

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/CoreData.h"
#include "core/WrittenFiles.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

NodeDecl writerDecl()
{
    NodeDecl d;
    d.type = "TestWriter";
    d.writesFiles = true;
    d.outputs = {PortDecl{"files", "Text", "", false}};
    return d;
}

OutputMap filesOutput(const std::string& files)
{
    return {{"files", std::make_shared<TextData>(files)}};
}

fs::path onlyRecord(const fs::path& cache)
{
    fs::path found;
    for (const auto& e : fs::directory_iterator(cache / "records"))
        if (e.path().filename().string().rfind("written-", 0) == 0) found = e.path();
    return found;
}

class WrittenFilesTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        cache = std::make_shared<DiskCache>(dir / "cache");
        fs::create_directories(dir / "out");
        std::ofstream(dir / "out/a.txt") << "alpha";
        std::ofstream(dir / "out/b.txt") << "beta";
        files = (dir / "out/a.txt").string() + "\n" + (dir / "out/b.txt").string();
        key.hi = 1;
        key.lo = 2;
    }
    test::TempDir dir;
    std::shared_ptr<DiskCache> cache;
    NodeDecl decl = writerDecl();
    std::string files;
    Key key;
};

}  // namespace

TEST_F(WrittenFilesTest, ARecordVerifiesWhileTheFilesAreUnchanged)
{
    const WrittenFiles written(cache, dir / "out");
    written.record(key, filesOutput(files));
    const auto outputs = written.verified(key, decl);
    ASSERT_TRUE(outputs);
    EXPECT_EQ(std::dynamic_pointer_cast<const TextData>(outputs->at("files"))->value, files);

    Key other = key;
    other.lo = 3;
    EXPECT_FALSE(written.verified(other, decl)) << "another key";
    EXPECT_FALSE(WrittenFiles(cache, dir / "elsewhere").verified(key, decl)) << "another --out";
    EXPECT_FALSE(WrittenFiles(nullptr, dir / "out").verified(key, decl)) << "no cache";

    std::ofstream(dir / "out/b.txt") << "betA";  // same size, other bytes
    EXPECT_FALSE(written.verified(key, decl));
    std::ofstream(dir / "out/b.txt") << "beta";
    EXPECT_TRUE(written.verified(key, decl));
    fs::remove(dir / "out/a.txt");
    EXPECT_FALSE(written.verified(key, decl));
}

TEST_F(WrittenFilesTest, DamagedOrForgedRecordsAreMisses)
{
    const WrittenFiles written(cache, dir / "out");
    written.record(key, filesOutput(files));
    const fs::path record = onlyRecord(dir / "cache");
    ASSERT_FALSE(record.empty());
    const auto good = nlohmann::json::parse(test::readFile(record));

    auto forge = [&](const std::string& text) {
        std::ofstream(record, std::ios::trunc) << text;
        return written.verified(key, decl).has_value();
    };
    EXPECT_FALSE(forge(good.dump().substr(0, 40))) << "truncated";
    EXPECT_FALSE(forge("[1, 2, 3]")) << "not an object";
    EXPECT_FALSE(forge(R"({"key": 5})")) << "wrong types";
    auto fewer = good;
    fewer["files"].erase(1);
    EXPECT_FALSE(forge(fewer.dump())) << "a file left out of the check";
    auto elsewhere = good;
    elsewhere["files"][0]["path"] = "/etc/hostname";
    EXPECT_FALSE(forge(elsewhere.dump())) << "checks a file the outputs do not name";
    auto negative = good;
    negative["files"][0]["size"] = -1;
    EXPECT_FALSE(forge(negative.dump()));
    EXPECT_TRUE(forge(good.dump())) << "the genuine record still verifies";
}

TEST_F(WrittenFilesTest, OnlyWritersWithATextFilesOutputKeepRecords)
{
    EXPECT_TRUE(WrittenFiles::keepsRecords(decl));
    NodeDecl logger = decl;
    logger.outputs = {PortDecl{"logged", "Text", "", false}};
    EXPECT_FALSE(WrittenFiles::keepsRecords(logger)) << "prints: must cook on every run";
    NodeDecl plain = decl;
    plain.writesFiles = false;
    EXPECT_FALSE(WrittenFiles::keepsRecords(plain));
}

}  // namespace cg
