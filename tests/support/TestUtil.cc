#include "support/TestUtil.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace cg::test {

TempDir::TempDir()
{
    static std::atomic<unsigned> counter{0};
    std::random_device rd;
    mPath = std::filesystem::temp_directory_path() /
            ("cloudgraph-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
             "-" + std::to_string(rd()));
    std::filesystem::create_directories(mPath);
}

TempDir::~TempDir()
{
    std::error_code ec;
    std::filesystem::remove_all(mPath, ec);
}

std::string readFile(const std::filesystem::path& p)
{
    std::ifstream f(p, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read " + p.string());
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

nlohmann::json readJson(const std::filesystem::path& p)
{
    return nlohmann::json::parse(readFile(p));
}

void writeFile(const std::filesystem::path& p, const std::string& text)
{
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + p.string());
}

CliProcess::CliProcess(const std::vector<std::string>& args)
{
    const std::string outPath = (mDir / "stdout").string();
    const std::string errPath = (mDir / "stderr").string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, outPath.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, errPath.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> argvStrings = {CLOUDGRAPH_CLI};
    argvStrings.insert(argvStrings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& s : argvStrings) argv.push_back(s.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, CLOUDGRAPH_CLI, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + std::string(CLOUDGRAPH_CLI));
    mPid = pid;
}

CliProcess::~CliProcess()
{
    if (!mWaited && mPid > 0) {
        ::kill(mPid, SIGKILL);
        int status = 0;
        waitpid(mPid, &status, 0);
    }
}

void CliProcess::kill(int signal) { ::kill(mPid, signal); }

std::string CliProcess::outputSoFar() const { return readFile(mDir / "stdout"); }

CliResult CliProcess::wait()
{
    int status = 0;
    while (waitpid(mPid, &status, 0) < 0) {
    }
    mWaited = true;
    CliResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1 - WTERMSIG(status);
    r.output = readFile(mDir / "stdout");
    r.errors = readFile(mDir / "stderr");
    return r;
}

CliResult runCli(const std::vector<std::string>& args) { return CliProcess(args).wait(); }

std::filesystem::path dataPath(const std::string& relative)
{
    return std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "tests" / "data" / relative;
}

std::string findOnPath(const std::string& name)
{
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        const std::filesystem::path candidate =
            std::filesystem::path(dir.empty() ? "." : dir) / name;
        if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return "";
}

ProgramResult runProgram(const std::vector<std::string>& argv, const std::filesystem::path& log,
                         bool alsoStderr)
{
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (alsoStderr) posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = -1;
    ProgramResult run;
    const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return run;
    int status = 0;
    if (::waitpid(pid, &status, 0) == pid && WIFEXITED(status)) run.status = WEXITSTATUS(status);
    run.output = readFile(log);
    return run;
}

}  // namespace cg::test
