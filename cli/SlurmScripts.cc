#include "cli/SlurmScripts.h"

#include <cstdio>

#include "core/Error.h"

namespace cg::cli {

namespace {

/// C0 controls and DEL: the characters a shell or sbatch may take as the end of a line.
bool isControl(char c)
{
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 || u == 0x7f;
}

/// `text` with its control characters spelled out, so that an error message quoting a hostile
/// value cannot itself move the cursor or end the line in the user's terminal.
std::string printable(const std::string& text)
{
    std::string out;
    for (char c : text) {
        if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if (c == '\t') {
            out += "\\t";
        } else if (isControl(c)) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
            out += hex;
        } else {
            out += c;
        }
    }
    return out;
}

/// Refuses a value bound for any line of a script: see checkFarmJob.
void checkScriptValue(const std::string& from, const std::string& value)
{
    for (char c : value) {
        if (isControl(c))
            throw InputError(from, "'" + printable(value) +
                                       "' holds a control character, which a farm script "
                                       "cannot carry safely (a newline would end a #SBATCH "
                                       "line and run the rest as a command on the cluster)");
    }
}

/// Refuses a value bound for a #SBATCH line: see checkFarmJob.
void checkSbatchValue(const std::string& from, const std::string& value)
{
    checkScriptValue(from, value);
    if (value.find('\\') != std::string::npos)
        throw InputError(from, "'" + value +
                                   "' holds a backslash, which sbatch reads as an escape in "
                                   "#SBATCH lines; use a path without one");
}

/// `path` as an sbatch filename pattern that names exactly it: "%%" is sbatch's literal '%'.
std::string literalPattern(const std::string& path)
{
    std::string out;
    for (char c : path) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
}

/// sbatch reads #SBATCH lines only before the first command: they all go here.
std::string header(const FarmJob& job, const std::string& stage, const std::string& logName,
                   const std::string& extraSbatchLine = {})
{
    std::string s = "#!/bin/bash\n";
    s += "#SBATCH --job-name=" + shellQuote("cloudgraph-" + stage + "-" + job.name) + "\n";
    // The log name's own patterns (%j, %A, %a) stay patterns; the directory is literal.
    s += "#SBATCH --output=" +
         shellQuote(literalPattern((job.farmDir / "logs").string()) + "/" + logName) + "\n";
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

void checkFarmJob(const FarmJob& job)
{
    checkSbatchValue("graph file name", job.name);
    checkSbatchValue("--out", job.farmDir.string());
    checkSbatchValue("working directory", job.workDir.string());
    checkScriptValue("cloudgraph executable", job.cloudgraph);
    for (const std::string& option : job.sbatchOptions) checkScriptValue("--sbatch", option);
    // Each value is named by the option before it; the first argument is the graph file.
    for (std::size_t i = 0; i < job.runArgs.size(); ++i) {
        const std::string from = i == 0                                   ? "graph file"
                                 : job.runArgs[i - 1].rfind("--", 0) == 0 ? job.runArgs[i - 1]
                                                                          : "run argument";
        checkScriptValue(from, job.runArgs[i]);
    }
}

FarmScripts slurmScripts(const FarmJob& job)
{
    checkFarmJob(job);
    const std::string reports = (job.farmDir / "reports").string();
    FarmScripts s;
    s.simulate =
        header(job, "simulate", "simulate-%j.log") +
        "# Cooks every simulation state of the graph into the shared cache, so that each\n"
        "# array task starts from the state before its first frame.\n" +
        runLine(job, {"--simulations-only", "--report", shellQuote(reports + "/simulate.json")});
    s.frames =
        header(job, "frames", "frames-%A_%a.log", "--array=0-" + std::to_string(job.chunks - 1)) +
        "# Task I cooks and writes frames of chunk I (" + std::to_string(job.chunk) +
        " frames each); frames whose files\n"
        "# verify from an earlier try are skipped, so resubmitting a failed task resumes it.\n" +
        runLine(job, {"--chunk", std::to_string(job.chunk), "--report",
                      shellQuote(reports + "/frames-") + "\"${SLURM_ARRAY_TASK_ID}\"" +
                          shellQuote(".json")});
    s.finish =
        header(job, "finish", "finish-%j.log") +
        "# Runs the whole range once every chunk is written: each frame's writers verify and\n"
        "# are skipped, and the nodes that gather every frame (EncodeVideo) cook.\n" +
        runLine(job, {"--report", shellQuote(reports + "/finish.json")});
    s.submit =
        "#!/bin/sh\n"
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
        "echo \"frames job $frames (array 0-" +
        std::to_string(job.chunks - 1) +
        ")\"\n"
        "echo \"finish job $finish\"\n";
    return s;
}

}  // namespace cg::cli
