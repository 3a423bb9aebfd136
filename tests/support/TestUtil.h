#pragma once
/// Helpers for tests: temporary directories, files, and running the cloudgraph CLI and other
/// programs.

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

/// The first executable `name` on PATH (/usr/local/bin:/usr/bin:/bin when PATH is unset), or
/// empty: a test of an outside program (ffmpeg, vdb_print) skips or fails clearly without it.
std::string findOnPath(const std::string& name);

/// What runProgram returns.
struct ProgramResult {
    int status = -1;     ///< the exit status; -1 when it did not start or did not exit normally
    std::string output;  ///< what it wrote to the log
};

/// Runs `argv` (argv[0] a path, as findOnPath gives) without a shell and waits for it. Its
/// stdout goes to the file `log`, and its stderr too with `alsoStderr` (else to the test's
/// stderr); the log comes back as output.
ProgramResult runProgram(const std::vector<std::string>& argv, const std::filesystem::path& log,
                         bool alsoStderr = true);

}  // namespace cg::test
