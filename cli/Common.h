#pragma once
/// What the subcommands share: option parsing, the registry with plugins, error reporting.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/Graph.h"
#include "core/Registry.h"

namespace cg::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

/// A minimal option scanner: flags, options with a value (repeatable), and positionals.
/// Every command takes -v (debug logging) and -q (errors only).
class OptionParser {
public:
    explicit OptionParser(const std::vector<std::string>& args) : mArgs(args), mFlags{"-v", "-q"} {}
    /// Declares an option that takes a value (e.g. "--out").
    void valueOption(const std::string& name) { mValueOptions.push_back(name); }
    /// Declares a flag (e.g. "--markdown").
    void flag(const std::string& name) { mFlags.push_back(name); }
    /// Parses and applies -v/-q; throws InputError("command line", ...) on an unknown option
    /// or a missing value.
    void parse();

    bool has(const std::string& name) const;
    std::optional<std::string> value(const std::string& name) const;  ///< the last one given
    std::vector<std::string> values(const std::string& name) const;   ///< all, in order
    const std::vector<std::string>& positionals() const { return mPositionals; }

private:
    const std::vector<std::string>& mArgs;
    std::vector<std::string> mValueOptions;
    std::vector<std::string> mFlags;
    std::vector<std::pair<std::string, std::string>> mSeen;
    std::vector<std::string> mPositionals;
};

/// `text` as a whole decimal integer in [min, max]; otherwise InputError naming `option`
/// ("--threads") and what is expected (`what`: "a thread count").
std::int64_t parseIntegerOption(const std::string& text, const std::string& option,
                                const std::string& what, std::int64_t min, std::int64_t max);

/// Sets up spdlog on stderr at info level (OptionParser::parse applies -v/-q).
void configureLogging();

/// Declares the options that add node types: --plugin and --python-nodes.
void declareNodeTypeOptions(OptionParser& opts);
/// The built-in nodes, plugins from CLOUDGRAPH_PLUGIN_PATH and --plugin, and the Python nodes
/// of --python-nodes files.
void buildRegistry(Registry& registry, const OptionParser& opts);

/// Declares the options that choose and edit a graph: --set, --allow-outside-out, and the
/// node type options.
void declareGraphOptions(OptionParser& opts);
/// How declareGraphOptions' flags load a graph (outside --out, graph programs).
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
