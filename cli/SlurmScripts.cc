#include "cli/SlurmScripts.h"

namespace cg::cli {

namespace {

/// sbatch reads #SBATCH lines only before the first command: they all go here.
std::string header(const FarmJob& job, const std::string& stage, const std::string& logName,
                   const std::string& extraSbatchLine = {})
{
    std::string s = "#!/bin/bash\n";
    s += "#SBATCH --job-name=" + shellQuote("cloudgraph-" + stage + "-" + job.name) + "\n";
    s += "#SBATCH --output=" + shellQuote((job.farmDir / "logs" / logName).string()) + "\n";
    s += "#SBATCH --chdir=" + shellQuote(job.workDir.string()) + "\n";
    if (!extraSbatchLine.empty()) s += "#SBATCH " + extraSbatchLine + "\n";
    for (const std::string& option : job.sbatchOptions) s += "#SBATCH " + option + "\n";
    s += "# Written by `cloudgraph farm`; see docs/farm.md.\n";
    s += "set -euo pipefail\n";
    return s;
}

std::string runLine(const FarmJob& job, const std::vector<std::string>& extra)
{
    std::string s = "exec " + shellQuote(job.cloudgraph) + " run";
    for (const std::string& a : job.runArgs) s += " " + shellQuote(a);
    for (const std::string& a : extra) s += " " + a;  // already shell words
    return s + "\n";
}

}  // namespace

std::string shellQuote(const std::string& text)
{
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

FarmScripts slurmScripts(const FarmJob& job)
{
    const std::string reports = (job.farmDir / "reports").string();
    FarmScripts s;
    s.simulate = header(job, "simulate", "simulate-%j.log") +
                 "# Cooks every simulation state of the graph into the shared cache, so that each\n"
                 "# array task starts from the state before its first frame.\n" +
                 runLine(job, {"--simulations-only", "--report", shellQuote(reports + "/simulate.json")});
    s.frames = header(job, "frames", "frames-%A_%a.log", "--array=0-" + std::to_string(job.chunks - 1)) +
               "# Task I cooks and writes frames of chunk I (" + std::to_string(job.chunk) +
               " frames each); frames whose files\n"
               "# verify from an earlier try are skipped, so resubmitting a failed task resumes it.\n" +
               runLine(job, {"--chunk", std::to_string(job.chunk), "--report",
                             shellQuote(reports + "/frames-") + "\"${SLURM_ARRAY_TASK_ID}\"" + shellQuote(".json")});
    s.finish = header(job, "finish", "finish-%j.log") +
               "# Runs the whole range once every chunk is written: each frame's writers verify and\n"
               "# are skipped, and the nodes that gather every frame (EncodeVideo) cook.\n" +
               runLine(job, {"--report", shellQuote(reports + "/finish.json")});
    s.submit = "#!/bin/sh\n"
               "# Written by `cloudgraph farm`: queues the simulation job, the frame array once it\n"
               "# has succeeded, and the finishing job after the whole array. Prints the job ids.\n"
               "set -eu\n"
               "here=$(cd \"$(dirname \"$0\")\" && pwd)\n"
               "simulate=$(sbatch --parsable \"$here/simulate.sbatch\")\n"
               "simulate=${simulate%%;*}\n"
               "frames=$(sbatch --parsable --dependency=afterok:\"$simulate\" \"$here/frames.sbatch\")\n"
               "frames=${frames%%;*}\n"
               "finish=$(sbatch --parsable --dependency=afterok:\"$frames\" \"$here/finish.sbatch\")\n"
               "finish=${finish%%;*}\n"
               "echo \"simulate job $simulate\"\n"
               "echo \"frames job $frames (array 0-" + std::to_string(job.chunks - 1) + ")\"\n"
               "echo \"finish job $finish\"\n";
    return s;
}

}  // namespace cg::cli
