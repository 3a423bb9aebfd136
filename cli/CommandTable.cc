#include "cli/CommandTable.h"

#include <algorithm>

namespace cg::cli {

namespace {

/// The options that add node types (nodes, dot, and every command that loads a graph).
std::vector<OptionSpec> nodeTypeOptions()
{
    return {
        {"--plugin", "PATH", "load a plugin library; repeatable"},
        {"--python-nodes", "FILE", "load the Python node classes of a .py file; repeatable"},
    };
}

/// The options that choose and edit a graph (Common.h's declareGraphOptions), then `own`.
std::vector<OptionSpec> withGraphOptions(std::vector<OptionSpec> own)
{
    own.push_back({"--set", "NODE.PARAM=VALUE",
                   "override a parameter (a JSON value or a bare string); repeatable"});
    for (OptionSpec& o : nodeTypeOptions()) own.push_back(std::move(o));
    own.push_back({"--allow-outside-out", "", "let output paths leave --out (absolute paths, ..)"});
    own.push_back({"--allow-graph-programs", "",
                   "let the graph name the programs it runs (EncodeVideo's ffmpeg)"});
    return own;
}

std::vector<CommandSpec> makeTable()
{
    return {
        {"run", "GRAPH [options]", "cook a graph for its frames",
         withGraphOptions({
             {"--frames", "A:B", "cook only frames A..B (inside the graph's range)"},
             {"--chunk", "N", "cook one chunk of N frames of that range (the last clamped)"},
             {"--task", "I", "the chunk --chunk cooks, from 0 (default: SLURM_ARRAY_TASK_ID)"},
             {"--simulations-only", "",
              "cook only the simulation nodes, into --cache (a farm's first job)"},
             {"--only", "NODE",
              "cook only NODE and what it needs (its writers' files alone, e.g. a one-frame "
              "look without the video); repeatable"},
             {"--out", "DIR", "where writers put files (default: out)"},
             {"--cache", "DIR", "on-disk cache shared across runs and processes"},
             {"--cache-memory-mb", "N", "in-memory cache budget in MiB (default 4096)"},
             {"--cache-limit", "SIZE",
              "after the run, remove the --cache's least recently used entries until it holds "
              "at most SIZE (e.g. 20G)"},
             {"--threads", "N", "worker threads (default: all cores)"},
             {"--report", "FILE",
              "JSON report: per node and frame, cooked or cache hit, why, time"},
             {"--farm-token", "T",
              "(written by `farm`) refuse a --cache that lacks the farm's token"},
         }),
         "Writers whose files from an earlier run still verify are skipped, with what only they "
         "need.\n"},
        {"farm", "GRAPH --chunk N --cache DIR [options]",
         "render on a Slurm cluster (docs/farm.md)",
         withGraphOptions({
             {"--chunk", "N", "frames of one array task (required)"},
             {"--cache", "DIR", "on-disk cache on a file system every node shares (required)"},
             {"--out", "DIR", "outputs (default: out); scripts, logs and reports go to DIR/slurm"},
             {"--scheduler", "NAME", "the scheduler: slurm (the one supported)"},
             {"--sbatch", "OPTION",
              "an #SBATCH line for both jobs, e.g. --sbatch=--partition=render; repeatable"},
             {"--submit", "", "queue the jobs with sbatch and print their ids"},
             {"--frames", "A:B", "render only frames A..B (inside the graph's range)"},
             {"--threads", "N", "worker threads of each job (default: all its cores)"},
             {"--cache-memory-mb", "N", "in-memory cache budget of each job in MiB (default 4096)"},
         }),
         "Writes the jobs' batch scripts; --submit also queues them.\n"},
        {"validate", "GRAPH [options]", "check a graph without cooking", withGraphOptions({}), ""},
        {"nodes", "[TYPE] [options]", "the node reference: every type, or one type in full",
         [] {
             std::vector<OptionSpec> o = {
                 {"--markdown", "", "the reference as Markdown (docs/nodes.md)"}};
             for (OptionSpec& t : nodeTypeOptions()) o.push_back(std::move(t));
             return o;
         }(),
         ""},
        {"dot", "GRAPH [options]", "the graph as Graphviz (for dot -Tsvg)", nodeTypeOptions(), ""},
        {"info", "FILE", "summary of a primitive-set file (.cgp), its checksums verified", {}, ""},
        {"sounding",
         "FILE [options]",
         "a sounding's LCL, LFC, EL, CAPE; its skew-T diagram",
         {{"--plot", "PNG", "draw the skew-T diagram into the PNG file"}},
         ""},
        {"serve", "GRAPH [options]", "edit the graph in the browser with a live preview",
         withGraphOptions({
             {"--port", "P", "listen on port P (default 8642; 0: any free port)"},
             {"--host", "H", "the address to listen on (default 127.0.0.1: this machine only)"},
             {"--allow-host", "NAME", "another name the browser may use for it; repeatable"},
             {"--out", "DIR", "where writers put files (default: out)"},
             {"--cache", "DIR", "on-disk cache shared across runs and processes"},
         }),
         "docs/serve.md describes the page and its API.\n"},
    };
}

std::string usageLine(const CommandSpec& command)
{
    return "cloudgraph " + command.name + (command.arguments.empty() ? "" : " ") +
           command.arguments;
}

/// `left` padded to `width`, then `right` (after two spaces when `left` is wider).
std::string column(const std::string& left, std::size_t width, const std::string& right)
{
    return left + std::string(left.size() < width ? width - left.size() : 2, ' ') + right + "\n";
}

}  // namespace

const std::vector<CommandSpec>& commandTable()
{
    static const std::vector<CommandSpec> table = makeTable();
    return table;
}

const CommandSpec* findCommand(const std::string& name)
{
    const auto& table = commandTable();
    const auto it = std::find_if(table.begin(), table.end(),
                                 [&](const CommandSpec& c) { return c.name == name; });
    return it == table.end() ? nullptr : &*it;
}

const std::vector<OptionSpec>& commonOptions()
{
    static const std::vector<OptionSpec> options = {
        {"-v", "", "more logging (debug)"},
        {"-q", "", "less logging (errors only)"},
        {"--help", "", "print this help and exit (also -h)"},
    };
    return options;
}

std::string commandHelp(const CommandSpec& command)
{
    std::string text = "usage: " + usageLine(command) + "\n\n" + command.summary + "\n";
    std::vector<const OptionSpec*> all;
    for (const OptionSpec& o : command.options) all.push_back(&o);
    for (const OptionSpec& o : commonOptions()) all.push_back(&o);
    const auto shown = [](const OptionSpec& o) {
        return "  " + o.name + (o.value.empty() ? "" : " " + o.value);
    };
    std::size_t width = 0;
    for (const OptionSpec* o : all) width = std::max(width, shown(*o).size() + 2);
    width = std::min<std::size_t>(width, 32);
    text += "\noptions:\n";
    for (const OptionSpec* o : all) text += column(shown(*o), width, o->help);
    if (!command.notes.empty()) text += "\n" + command.notes;
    return text;
}

std::string overviewHelp()
{
    std::string text =
        "cloudgraph - node-graph tool that animates the growth of cumulus clouds\n\nusage:\n";
    std::size_t width = 0;
    for (const CommandSpec& c : commandTable()) width = std::max(width, usageLine(c).size() + 4);
    for (const CommandSpec& c : commandTable())
        text += column("  " + usageLine(c), width, c.summary);
    text += column("  cloudgraph help [COMMAND]", width, "this help, or a command's");
    text += column("  cloudgraph --version", width, "the version");
    text +=
        "\n`cloudgraph COMMAND --help` (or -h) lists a command's options. Every command takes -v\n"
        "(debug logging) and -q (errors only).\n\n"
        "Plugins are also loaded from the absolute directories in CLOUDGRAPH_PLUGIN_PATH "
        "(colon-separated).\n"
        "Exit codes: 0 ok, 2 bad input (graph, parameter, file), 1 internal failure.\n";
    return text;
}

}  // namespace cg::cli
