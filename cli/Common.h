#pragma once
/// What the subcommands share: option parsing, the registry with plugins, error reporting.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/CommandTable.h"
#include "core/Graph.h"
#include "core/Registry.h"

namespace cg::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

/// A minimal option scanner: flags, options with a value (repeatable), and positionals. The
/// options are those of the command's entry in CommandTable and the common ones (-v: debug
/// logging, -q: errors only, --help or -h).
class OptionParser {
public:
    /// `command` names an entry of commandTable() (std::logic_error when none does).
    OptionParser(const std::vector<std::string>& args, const std::string& command);
    /// True when -h or --help stands where an option may (not as another option's value),
    /// whatever else the arguments hold. Throws nothing.
    bool asksForHelp() const;
    /// Parses and applies -v/-q; throws InputError("command line", ...) on an unknown option
    /// or a missing value, pointing at `cloudgraph COMMAND --help`.
    void parse();

    bool has(const std::string& name) const;
    std::optional<std::string> value(const std::string& name) const;  ///< the last one given
    std::vector<std::string> values(const std::string& name) const;   ///< all, in order
    const std::vector<std::string>& positionals() const { return mPositionals; }

private:
    /// The option `name` declares ("-h" is "--help"), or nullptr.
    const OptionSpec* find(const std::string& name) const;

    const std::vector<std::string>& mArgs;
    const CommandSpec& mCommand;
    std::vector<std::pair<std::string, std::string>> mSeen;
    std::vector<std::string> mPositionals;
};

/// `text` as a whole decimal integer in [min, max]; otherwise InputError naming `option`
/// ("--threads") and what is expected (`what`: "a thread count").
std::int64_t parseIntegerOption(const std::string& text, const std::string& option,
                                const std::string& what, std::int64_t min, std::int64_t max);

/// Sets up spdlog on stderr at info level (OptionParser::parse applies -v/-q).
void configureLogging();

/// The built-in nodes, plugins from CLOUDGRAPH_PLUGIN_PATH and --plugin, and the Python nodes
/// of --python-nodes files.
void buildRegistry(Registry& registry, const OptionParser& opts);

/// How the graph options' flags (CommandTable) load a graph (outside --out, graph programs).
LoadOptions graphLoadOptions(const OptionParser& opts);
/// Builds the registry (with --plugin), loads the one positional graph file and applies
/// every --set. Throws InputError on any bad input.
Graph loadGraphFromOptions(const OptionParser& opts, Registry& registry, const char* command);

/// Refuses (InputError, exit 2), before anything cooks, what would otherwise fail only at the
/// first write, after minutes of cooking: an `out` that cannot be created or written (read
/// only, full) and, for every output path of `targets` and the nodes they need (the graph's
/// sinks when empty) at each frame of `frames`, a directory where the file goes or a
/// directory of its path that leads out of `out` through a symbolic link (unless the graph
/// allows paths outside it). The error names the node's parameter and the file.
void checkOutputPlaces(const Graph& graph, const std::vector<std::string>& targets,
                       FrameRange frames, const std::filesystem::path& out);

/// Runs `body`, turning exceptions into a message on stderr and an exit code.
int guarded(const std::function<int()>& body);

}  // namespace cg::cli
