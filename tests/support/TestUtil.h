#pragma once
/// Helpers for tests: temporary directories, files, and running the cloudgraph CLI.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cg::test {

/// A fresh directory under the system temp dir, removed with its contents on destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return mPath; }
    std::filesystem::path operator/(const std::string& name) const { return mPath / name; }

private:
    std::filesystem::path mPath;
};

std::string readFile(const std::filesystem::path& p);
nlohmann::json readJson(const std::filesystem::path& p);
void writeFile(const std::filesystem::path& p, const std::string& text);

struct CliResult {
    int exitCode = -1;   ///< the exit status; -1 - signal number when killed by a signal
    std::string output;  ///< stdout
    std::string errors;  ///< stderr
};

/// The cloudgraph binary running in the background (no shell), output captured to files.
class CliProcess {
public:
    explicit CliProcess(const std::vector<std::string>& args);
    ~CliProcess();
    CliProcess(const CliProcess&) = delete;
    CliProcess& operator=(const CliProcess&) = delete;
    void kill(int signal);
    /// What it has written to stdout so far.
    std::string outputSoFar() const;
    /// Waits for the process to end and collects its output.
    CliResult wait();

private:
    TempDir mDir;
    int mPid = -1;
    bool mWaited = false;
};

/// Runs the cloudgraph binary with `args` (no shell), waiting for it to finish.
CliResult runCli(const std::vector<std::string>& args);

/// Path of a file under the source tree's tests/data.
std::filesystem::path dataPath(const std::string& relative);

}  // namespace cg::test
