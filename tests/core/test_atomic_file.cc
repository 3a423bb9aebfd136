// util::AtomicOutput: nothing partial under the final name, fsync failures reported, and the temp
// files of killed writers removed at the next run while live writers' files stay.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "support/TestUtil.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

/// The pid of a process that has ended (and been reaped): no live writer can own it.
pid_t deadPid()
{
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return pid;
}

/// The temp name `live` would have if process `pid` had made it.
fs::path asIfWrittenBy(const fs::path& live, pid_t pid)
{
    std::string name = live.filename().string();
    const std::string ours = "-" + std::to_string(::getpid()) + "-";
    const auto at = name.find(ours);
    EXPECT_NE(at, std::string::npos) << name;
    name.replace(at, ours.size(), "-" + std::to_string(pid) + "-");
    return live.parent_path() / name;
}

}  // namespace

TEST(AtomicFile, CommitReplacesTheTargetAndAnAbandonedWriteLeavesNothing)
{
    test::TempDir dir;
    util::writeFileAtomically(dir / "a.txt", "first");
    util::writeFileAtomically(dir / "a.txt", "second");
    EXPECT_EQ(test::readFile(dir / "a.txt"), "second");
    {
        util::AtomicOutput out(dir / "b.txt");
        test::writeFile(out.tempPath(), "partial");
    }
    EXPECT_FALSE(fs::exists(dir / "b.txt"));
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir.path())) files += e.is_regular_file();
    EXPECT_EQ(files, 1u);
    EXPECT_THROW(util::writeFileAtomically(dir / "missing-dir" / "c.txt", "x"), std::runtime_error);
}

TEST(AtomicFile, OrphansOfDeadWritersAreRemovedAndLiveWritersKeepTheirs)
{
    test::TempDir dir;
    util::AtomicOutput live(dir / "frame.0001.png");
    test::writeFile(live.tempPath(), "being written");
    const fs::path orphan = asIfWrittenBy(live.tempPath(), deadPid());
    test::writeFile(orphan, "killed mid-write");
    // Another host's writer: its pid means nothing here, only its age does.
    const fs::path foreignFresh = dir / ".frame.0002.png.0badf00d-1-0.cgtmp";
    const fs::path foreignOld = dir / ".frame.0003.png.0badf00d-1-0.cgtmp";
    test::writeFile(foreignFresh, "x");
    test::writeFile(foreignOld, "x");
    fs::last_write_time(foreignOld, fs::file_time_type::clock::now() - std::chrono::hours(25));
    test::writeFile(dir / "frame.0000.png", "an output");
    test::writeFile(dir / ".hidden-user-file", "not ours");

    EXPECT_EQ(util::removeOrphanedTemporaries(dir.path()), 2u);
    EXPECT_FALSE(fs::exists(orphan));
    EXPECT_FALSE(fs::exists(foreignOld));
    EXPECT_TRUE(fs::exists(live.tempPath()));
    EXPECT_TRUE(fs::exists(foreignFresh));
    EXPECT_TRUE(fs::exists(dir / "frame.0000.png"));
    EXPECT_TRUE(fs::exists(dir / ".hidden-user-file"));
    live.commit();
    EXPECT_EQ(test::readFile(dir / "frame.0001.png"), "being written");
}

TEST(AtomicFile, TheNextRunRemovesTheTemporariesOfAKilledRun)
{
    test::TempDir dir;
    const std::string graph = test::dataPath("good/chain.json").string();
    ASSERT_EQ(test::runCli({"run", graph, "--out", (dir / "out").string(), "-q"}).exitCode, 0);
    // Where the graph's writer writes: a killed run leaves its temp files there.
    fs::path written;
    for (const auto& e : fs::recursive_directory_iterator(dir / "out"))
        if (e.is_regular_file()) written = e.path();
    ASSERT_FALSE(written.empty());
    util::AtomicOutput probe(written);
    const fs::path orphan = asIfWrittenBy(probe.tempPath(), deadPid());
    test::writeFile(orphan, "killed mid-write");
    ASSERT_EQ(test::runCli({"run", graph, "--out", (dir / "out").string(), "-q"}).exitCode, 0);
    EXPECT_FALSE(fs::exists(orphan));
}

}  // namespace cg
