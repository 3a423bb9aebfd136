// Fuzz target: the graph loader (cg::parseGraph) with every built-in node type. Bad input must
// end in cg::InputError; any other exception, a sanitizer report, a hang or unbounded memory is
// a finding. A graph that loads must survive the save/load round trip unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"

namespace {

const cg::Registry& registry()
{
    static const cg::Registry* r = [] {
        auto* reg = new cg::Registry;  // never freed: lives as long as the process
        cg::registerBuiltinNodes(*reg);
        return reg;
    }();
    return *r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    spdlog::set_level(spdlog::level::off);
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string saved;
    try {
        const cg::Graph graph = cg::parseGraph(text, "fuzz.json", registry());
        saved = cg::graphToJson(graph).dump(2);
    } catch (const cg::InputError&) {
        return 0;
    }
    // Outside the try: the saved form of a valid graph must load (no InputError allowed).
    const cg::Graph back = cg::parseGraph(saved, "saved.json", registry());
    if (cg::graphToJson(back).dump(2) != saved) {
        std::fprintf(stderr, "graph changed in the save/load round trip:\n%s\n", saved.c_str());
        std::abort();
    }
    return 0;
}
