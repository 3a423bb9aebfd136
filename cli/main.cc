// cloudgraph: cook node graphs that grow cumulus clouds. See --help.

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "util/FreedMemory.h"

namespace {

const char* kUsage = R"(cloudgraph - node-graph tool that animates the growth of cumulus clouds

usage:
  cloudgraph run GRAPH [options]     cook a graph for its frames
      --frames A:B                   cook only frames A..B (inside the graph's range)
      --chunk N [--task I]           cook chunk I of N frames each of that range (the last clamped);
                                     without --task, I is SLURM_ARRAY_TASK_ID
      --simulations-only             cook only the simulation nodes, into --cache (a farm's first job)
      --set NODE.PARAM=VALUE         override a parameter (JSON value or bare string); repeatable
      --out DIR                      where writers put files (default: out)
      --cache DIR                    on-disk cache shared across runs and processes
      --cache-memory-mb N            in-memory cache budget (default 4096)
      --threads N                    worker threads (default: all cores)
      --report FILE                  JSON report: per node and frame, cooked or cache hit, why, time
      --plugin PATH                  load a plugin library; repeatable
      --python-nodes FILE            load the Python node classes of a .py file; repeatable
      --allow-outside-out            let output paths leave --out (absolute paths, ..)
      --allow-graph-programs         let the graph name the programs it runs (EncodeVideo's ffmpeg)
      --farm-token T                 (written by `farm`) refuse a --cache that lacks the farm's token
      -v / -q                        more / less logging
  Writers whose files from an earlier run still verify are skipped, with what only they need.
  cloudgraph farm GRAPH --chunk N --cache DIR [options]   render on a Slurm cluster (docs/farm.md)
      --out DIR                      outputs; the scripts, logs and reports go to DIR/slurm
      --scheduler slurm              the scheduler (the one supported)
      --sbatch OPTION                an #SBATCH line for both jobs, e.g. --sbatch=--partition=render
      --submit                       queue the jobs with sbatch and print their ids
      also --frames, --set, --plugin, --python-nodes, --threads, --allow-* as for run
  cloudgraph validate GRAPH [--set ...] [--plugin PATH] [--python-nodes FILE]
                                                          check a graph without cooking
  cloudgraph nodes [TYPE] [--markdown] [--plugin ...] [--python-nodes ...]   the node reference
  cloudgraph dot GRAPH [--plugin ...] [--python-nodes ...]                  the graph as Graphviz
  cloudgraph info FILE                                    summary of a primitive-set file (.cgp)
  cloudgraph sounding FILE [--plot PNG]                   a sounding's LCL, LFC, EL, CAPE; its skew-T
  cloudgraph serve GRAPH [options]   edit the graph in the browser with a live preview
      --port P                       listen on port P (default 8642; 0: any free port)
      --host H                       the address to listen on (default 127.0.0.1: this machine only)
      --allow-host NAME              another name the browser may use for it (repeatable)
      --out DIR, --cache DIR         as for run
  cloudgraph --help | --version
Every command takes -v (debug logging) and -q (errors only).

Plugins are also loaded from the absolute directories in CLOUDGRAPH_PLUGIN_PATH (colon-separated).
Exit codes: 0 ok, 2 bad input (graph, parameter, file), 1 internal failure.
)";

}  // namespace

int main(int argc, char** argv)
{
    using namespace cg::cli;
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? kExitBadInput : kExitOk;
    }
    if (args[0] == "--version") {
        std::printf("cloudgraph %s\n", CLOUDGRAPH_VERSION);
        return kExitOk;
    }
    configureLogging();
    cg::util::keepFreedMemoryForReuse();
    const std::string command = args[0];
    args.erase(args.begin());
    if (command == "run") return runCommand(args);
    if (command == "farm") return farmCommand(args);
    if (command == "validate") return validateCommand(args);
    if (command == "nodes") return nodesCommand(args);
    if (command == "dot") return dotCommand(args);
    if (command == "info") return infoCommand(args);
    if (command == "sounding") return soundingCommand(args);
    if (command == "serve") return serveCommand(args);
    std::fprintf(stderr, "error: unknown command '%s'\n\n%s", command.c_str(), kUsage);
    return kExitBadInput;
}
