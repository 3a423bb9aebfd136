// Fuzz target: the bodies of serve's /api/* requests, through GraphServer::handle (the same
// function the HTTP server calls) on a small graph that cooks in microseconds. The first
// byte picks the route; the rest is the body (or the query of a GET). Every reply must be a
// JSON or PNG reply with a 2xx, 400, 403, 404, 405 or 409 status: an exception escaping the
// handler (which the server would answer 500), a sanitizer report or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include <spdlog/spdlog.h>

#include "cli/GraphServer.h"
#include "cli/http/HttpMessage.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"

namespace {

const char* kGraph = R"({
  "cloudgraph": 1,
  "frames": {"start": 0, "end": 3},
  "nodes": {
    "field": {"type": "RandomField", "params": {"width": 8, "height": 8, "seed": 1}},
    "stats": {"type": "Statistics", "inputs": {"values": "field.values"}},
    "write": {"type": "WriteText", "params": {"file": "stats.####.txt"},
              "inputs": {"text": "stats.summary"}}
  }
})";

struct Fixture {
    cg::Registry registry;
    std::filesystem::path dir;
    std::unique_ptr<cg::cli::GraphServer> server;

    Fixture()
    {
        cg::registerBuiltinNodes(registry);
        char templ[] = "/tmp/fuzz_serve_api.XXXXXX";
        dir = ::mkdtemp(templ);
        static const std::filesystem::path made = dir;
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(made, ec);
        });
        std::ofstream(dir / "graph.json") << kGraph;
        cg::cli::ServeOptions options;
        options.graphFile = dir / "graph.json";
        options.webDir = CLOUDGRAPH_WEB_DIR;
        options.outDir = (dir / "out").string();
        options.port = 0;
        server = std::make_unique<cg::cli::GraphServer>(registry, options);
    }
};

Fixture& fixture()
{
    static Fixture* f = new Fixture;  // never freed: lives as long as the process
    return *f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    spdlog::set_level(spdlog::level::off);
    if (size == 0) return 0;
    Fixture& f = fixture();
    // The route by the first byte (seeds name it): POSTs take the rest as their body.
    struct Route {
        const char* method;
        const char* path;
    };
    static const Route kRoutes[] = {
        {"POST", "/api/graph"}, {"POST", "/api/param"},  {"POST", "/api/cook"},
        {"POST", "/api/save"},  {"POST", "/api/cancel"}, {"GET", "/api/preview"},
        {"GET", "/api/graph"},  {"GET", "/api/version"}, {"GET", "/"},
        {"POST", "/api/paint"}};
    const Route& route = kRoutes[data[0] % std::size(kRoutes)];
    const std::string rest(reinterpret_cast<const char*>(data + 1), size - 1);
    cg::cli::http::Request req;
    req.headers = {{"host", "127.0.0.1:0"},
                   {"content-type", "application/json"},
                   {"x-cloudgraph-token", f.server->token()}};
    req.method = route.method;
    req.path = route.path;
    if (req.method == "POST") {
        req.body = rest;
    } else {
        // The rest as the query's node and port, split at its first NUL.
        const std::size_t nul = rest.find('\0');
        req.query["node"] = rest.substr(0, nul);
        if (nul != std::string::npos) req.query["port"] = rest.substr(nul + 1);
    }
    req.target = req.path;
    const cg::cli::http::Response res = f.server->handle(req);
    const bool known = (res.status >= 200 && res.status < 300) || res.status == 400 ||
                       res.status == 403 || res.status == 404 || res.status == 405 ||
                       res.status == 409;
    if (!known) {
        std::fprintf(stderr, "status %d for %s: %s\n", res.status, req.path.c_str(),
                     res.body.c_str());
        std::abort();
    }
    return 0;
}
