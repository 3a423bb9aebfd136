#pragma once
/// The subcommands and their options, one table that both the option parser (OptionParser)
/// and the help text read: an option the table lacks is refused, and every option in it is
/// listed by `cloudgraph COMMAND --help` with its line of description.

#include <string>
#include <vector>

namespace cg::cli {

/// One option of a command.
struct OptionSpec {
    std::string name;   ///< "--frames"
    std::string value;  ///< what follows it in the usage ("A:B"); empty for a flag
    std::string help;   ///< one line: what it does, its default, whether it repeats
};

/// One subcommand.
struct CommandSpec {
    std::string name;                 ///< "run"
    std::string arguments;            ///< its positionals in the usage line: "GRAPH", "[TYPE]"
    std::string summary;              ///< one line, for `cloudgraph --help`
    std::vector<OptionSpec> options;  ///< its own; every command also takes commonOptions()
    std::string notes;                ///< further lines for its --help ("" for none)
};

/// Every subcommand, in the order `cloudgraph --help` lists them.
const std::vector<CommandSpec>& commandTable();
/// The command named `name`, or nullptr.
const CommandSpec* findCommand(const std::string& name);
/// The options every command takes: -v, -q and --help (also spelled -h).
const std::vector<OptionSpec>& commonOptions();

/// `cloudgraph COMMAND --help`: the usage line, the summary, each option with its line.
std::string commandHelp(const CommandSpec& command);
/// `cloudgraph --help`: each command's usage line and summary, and what they share.
std::string overviewHelp();

}  // namespace cg::cli
