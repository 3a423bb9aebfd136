// cloudgraph: cook node graphs that grow cumulus clouds. See --help; each command's options
// and their help are in CommandTable.cc.

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cli/CommandTable.h"
#include "cli/Commands.h"
#include "cli/Common.h"
#include "util/FreedMemory.h"

int main(int argc, char** argv)
{
    using namespace cg::cli;
    const std::map<std::string, int (*)(const Args&)> commands = {
        {"run", runCommand},           {"farm", farmCommand},  {"validate", validateCommand},
        {"nodes", nodesCommand},       {"dot", dotCommand},    {"info", infoCommand},
        {"sounding", soundingCommand}, {"serve", serveCommand}};
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" ||
        (args[0] == "help" && args.size() == 1)) {
        std::fputs(overviewHelp().c_str(), args.empty() ? stderr : stdout);
        return args.empty() ? kExitBadInput : kExitOk;
    }
    if (args[0] == "--version") {
        std::printf("cloudgraph %s\n", CLOUDGRAPH_VERSION);
        return kExitOk;
    }
    if (args[0] == "help") {  // help COMMAND
        if (const CommandSpec* command = findCommand(args[1]); command && args.size() == 2) {
            std::fputs(commandHelp(*command).c_str(), stdout);
            return kExitOk;
        }
        std::fprintf(stderr, "error: help takes one command; the commands are:\n\n%s",
                     overviewHelp().c_str());
        return kExitBadInput;
    }
    const std::string name = args[0];
    args.erase(args.begin());
    const CommandSpec* command = findCommand(name);
    const auto run = commands.find(name);
    if (!command || run == commands.end()) {
        std::fprintf(stderr, "error: unknown command '%s'\n\n%s", name.c_str(),
                     overviewHelp().c_str());
        return kExitBadInput;
    }
    if (OptionParser(args, name).asksForHelp()) {
        std::fputs(commandHelp(*command).c_str(), stdout);
        return kExitOk;
    }
    configureLogging();
    cg::util::keepFreedMemoryForReuse();
    return run->second(args);
}
