#pragma once
/// The batch scripts `cloudgraph farm --scheduler slurm` writes: a job that cooks the
/// graph's simulation states into the shared cache, a job array whose task I renders
/// chunk I of the frames, a last job that runs what gathers every frame (EncodeVideo) and
/// verifies every frame's files, and a submit script that queues each job after the one
/// before it succeeds (--dependency=afterok).

#include <filesystem>
#include <string>
#include <vector>

namespace cg::cli {

struct FarmJob {
    std::string name;                        ///< job name stem (the graph file's stem)
    std::string cloudgraph;                  ///< the executable, absolute
    std::vector<std::string> runArgs;        ///< `run` arguments both jobs share (absolute paths)
    std::filesystem::path farmDir;           ///< scripts here; logs/ and reports/ below it
    std::filesystem::path workDir;           ///< the jobs' working directory
    int chunk = 1;                           ///< frames per array task
    int chunks = 1;                          ///< array tasks: 0 .. chunks-1
    std::vector<std::string> sbatchOptions;  ///< extra "#SBATCH" lines, e.g. --partition=render
};

struct FarmScripts {
    std::string simulate;  ///< simulate.sbatch
    std::string frames;    ///< frames.sbatch
    std::string finish;    ///< finish.sbatch
    std::string submit;    ///< submit.sh
};

/// Throws InputError, naming the option or file a value came from, when a value of `job` cannot
/// be written into a script as it is. The scripts run with the submitting user's rights on
/// every node, and #SBATCH lines are shell comments that a newline ends, so no value may hold
/// a control character (C0 or DEL); a value inside a #SBATCH line (the graph file's name, --out,
/// the working directory) may also not hold a backslash, which sbatch reads as an escape even
/// inside quotes. A '%' is kept: it is written as "%%" in --output, where sbatch reads patterns
/// such as %j, and as it is in --job-name and --chdir, which take it literally.
void checkFarmJob(const FarmJob& job);

/// The scripts for `job`; calls checkFarmJob first, so nothing unsafe is ever returned.
FarmScripts slurmScripts(const FarmJob& job);

/// `text` as one POSIX shell word.
std::string shellQuote(const std::string& text);

}  // namespace cg::cli
