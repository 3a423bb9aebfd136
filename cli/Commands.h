#pragma once
/// The cloudgraph subcommands. Each returns the process exit code:
/// 0 ok, 2 bad input (graph, parameter, file), 1 internal failure.

#include <string>
#include <vector>

namespace cg::cli {

using Args = std::vector<std::string>;

int runCommand(const Args& args);
int farmCommand(const Args& args);
int validateCommand(const Args& args);
int nodesCommand(const Args& args);
int dotCommand(const Args& args);
int infoCommand(const Args& args);
int soundingCommand(const Args& args);
int serveCommand(const Args& args);

}  // namespace cg::cli
