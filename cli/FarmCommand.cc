// cloudgraph farm GRAPH --chunk N --cache DIR [--out DIR] [--scheduler slurm] [--frames A:B]
//                       [--set ...] [--plugin ...] [--threads N] [--sbatch OPTION]... [--submit]
// Writes the batch scripts that render the graph on a Slurm cluster; --submit queues them.

#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include <spdlog/spdlog.h>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "cli/FarmToken.h"
#include "cli/FrameChunks.h"
#include "cli/SlurmScripts.h"
#include "core/DiskCache.h"
#include "core/Error.h"
#include "util/AtomicFile.h"

extern char** environ;

namespace cg::cli {

namespace {

namespace fs = std::filesystem;

/// The arguments of `run` that both jobs share: the graph, its edits, the shared folders.
std::vector<std::string> sharedRunArgs(const OptionParser& opts, const fs::path& cache,
                                       const fs::path& out)
{
    std::vector<std::string> args = {
        fs::absolute(opts.positionals()[0]).lexically_normal().string(), "--cache", cache.string(),
        "--out", out.string()};
    for (const std::string& s : opts.values("--set")) args.insert(args.end(), {"--set", s});
    for (const char* o : {"--plugin", "--python-nodes"})
        for (const std::string& p : opts.values(o))
            args.insert(args.end(), {o, fs::absolute(p).lexically_normal().string()});
    for (const char* o : {"--frames", "--threads", "--cache-memory-mb"})
        if (auto v = opts.value(o)) args.insert(args.end(), {o, *v});
    for (const char* f : {"--allow-outside-out", "--allow-graph-programs"})
        if (opts.has(f)) args.emplace_back(f);
    return args;
}

void writeScript(const fs::path& path, const std::string& text)
{
    util::writeFileAtomically(path, text);
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

/// Runs the submit script (it calls sbatch) with our stdout and stderr; throws when it fails.
void submit(const fs::path& script)
{
    const std::string path = script.string();
    char sh[] = "/bin/sh";
    std::vector<char*> argv = {sh, const_cast<char*>(path.c_str()), nullptr};
    pid_t pid = 0;
    if (posix_spawn(&pid, sh, nullptr, nullptr, argv.data(), environ) != 0)
        throw std::runtime_error("cannot start /bin/sh for " + path);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw std::runtime_error("waitpid failed for " + path);
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error(
            "submitting failed (is Slurm's sbatch on PATH?); the scripts are in " +
            script.parent_path().string() + ", run " + path + " again to retry");
}

}  // namespace

int farmCommand(const Args& args)
{
    OptionParser opts(args, "farm");
    return guarded([&] {
        opts.parse();
        if (const auto s = opts.value("--scheduler"); s && *s != "slurm")
            throw InputError("--scheduler",
                             "'" + *s + "' is not supported; the one scheduler is slurm");
        const auto chunkText = opts.value("--chunk");
        if (!chunkText)
            throw InputError("--chunk", "farm needs --chunk N, the frames of one array task");
        const auto cacheDir = opts.value("--cache");
        if (!cacheDir)
            throw InputError("--cache",
                             "farm needs --cache DIR on a file system every node shares");
        for (const std::string& option : opts.values("--sbatch"))
            if (option.rfind("--", 0) != 0)
                throw InputError("--sbatch " + option,
                                 "must be one sbatch option such as --partition=render");

        Registry registry;
        const Graph graph = loadGraphFromOptions(opts, registry, "farm");
        const FrameRange range = opts.value("--frames")
                                     ? parseFrameRange(*opts.value("--frames"), graph.frames)
                                     : graph.frames;
        FarmJob job;
        job.chunk = parseChunkSize(*chunkText);
        job.chunks = chunkCount(range, job.chunk);

        const fs::path cache = fs::absolute(*cacheDir).lexically_normal();
        const fs::path out = fs::absolute(opts.value("--out").value_or("out")).lexically_normal();
        job.farmDir = out / "slurm";
        job.workDir = fs::current_path();
        job.name = fs::path(opts.positionals()[0]).stem().string();
        job.cloudgraph = fs::read_symlink("/proc/self/exe").string();
        job.runArgs = sharedRunArgs(opts, cache, out);
        job.sbatchOptions = opts.values("--sbatch");
        // A value the scripts cannot carry is refused before the cache or --out is touched.
        checkFarmJob(job);

        const DiskCache diskCache(cache);  // refuses a directory it cannot write
        const std::string token = leaveFarmToken(diskCache);
        job.runArgs.insert(job.runArgs.end(), {"--farm-token", token});
        const FarmScripts scripts = slurmScripts(job);
        fs::create_directories(job.farmDir / "logs");
        fs::create_directories(job.farmDir / "reports");
        writeScript(job.farmDir / "simulate.sbatch", scripts.simulate);
        writeScript(job.farmDir / "frames.sbatch", scripts.frames);
        writeScript(job.farmDir / "finish.sbatch", scripts.finish);
        writeScript(job.farmDir / "submit.sh", scripts.submit);
        spdlog::info("frames {}..{} in {} array tasks of {} frames; scripts in {}", range.start,
                     range.end, job.chunks, job.chunk, job.farmDir.string());
        if (opts.has("--submit")) {
            submit(job.farmDir / "submit.sh");
        } else {
            spdlog::info("submit with: {}", (job.farmDir / "submit.sh").string());
        }
        return kExitOk;
    });
}

}  // namespace cg::cli
