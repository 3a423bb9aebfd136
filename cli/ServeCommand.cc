// cloudgraph serve GRAPH [--port P] [--host H] [--allow-host NAME]... [--out DIR] [--cache DIR]
//                       [--plugin ...]
//
// The graph editor and live preview in the browser (docs/serve.md).

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include <pthread.h>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "cli/GraphServer.h"
#include "core/DiskCache.h"
#include "core/Error.h"

namespace cg::cli {

namespace {

/// The page's folder: CLOUDGRAPH_WEB_DIR; else share/cloudgraph/web beside an installed
/// binary's bin/ (cli/CMakeLists.txt's install rules); else the source tree's web/ this
/// binary was built from.
std::filesystem::path webDir()
{
    if (const char* dir = std::getenv("CLOUDGRAPH_WEB_DIR"); dir && *dir) return dir;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path installed =
        exe.parent_path().parent_path() / "share" / "cloudgraph" / "web";
    if (!ec && std::filesystem::is_directory(installed, ec)) return installed;
    return CLOUDGRAPH_WEB_DIR;
}

}  // namespace

int serveCommand(const Args& args)
{
    OptionParser opts(args, "serve");
    return guarded([&] {
        opts.parse();
        if (opts.positionals().size() != 1)
            throw InputError("command line", "serve needs exactly one graph file");
        ServeOptions o;
        o.graphFile = opts.positionals()[0];
        o.webDir = webDir();
        o.outDir = opts.value("--out").value_or("out");
        o.cacheDir = opts.value("--cache").value_or("");
        o.host = opts.value("--host").value_or("127.0.0.1");
        o.allowedHosts = opts.values("--allow-host");
        // As `run` does: a cache that cannot be made is refused before anything is served.
        if (!o.cacheDir.empty()) DiskCache check(o.cacheDir);
        if (const auto port = opts.value("--port"))
            o.port = static_cast<int>(parseIntegerOption(*port, "--port", "a port", 0, 65535));
        o.load = graphLoadOptions(opts);
        o.sets = opts.values("--set");
        Registry registry;
        buildRegistry(registry, opts);

        // SIGINT and SIGTERM stop the server from a thread of their own, so no handler runs
        // inside a request; every thread started from here on inherits the blocked set.
        sigset_t stopSignals;
        sigemptyset(&stopSignals);
        sigaddset(&stopSignals, SIGINT);
        sigaddset(&stopSignals, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

        GraphServer server(registry, o);
        const int port = server.bind();
        const bool ipv6 = o.host.find(':') != std::string::npos;
        std::printf("serving %s at http://%s%s%s:%d/ (Ctrl-C stops)\n", o.graphFile.c_str(),
                    ipv6 ? "[" : "", o.host.c_str(), ipv6 ? "]" : "", port);
        std::fflush(stdout);
        std::thread waiter([&] {
            int signal = 0;
            sigwait(&stopSignals, &signal);
            server.stop();
        });
        server.listen();
        // listen() also returns when the socket fails: wake the waiter so that it ends.
        // NOLINTNEXTLINE(bugprone-bad-signal-to-kill-thread): SIGTERM is blocked; sigwait takes it.
        pthread_kill(waiter.native_handle(), SIGTERM);
        waiter.join();
        return kExitOk;
    });
}

}  // namespace cg::cli
