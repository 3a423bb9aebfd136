/// A plugin built against another engine whose static constructor has a visible effect: the
/// loader must refuse it by its stamp, before dlopen would run the constructor.

#include <cstdlib>

#include "core/Plugin.h"

static constexpr int kEngineAbiVersion = CLOUDGRAPH_PLUGIN_ABI_VERSION;
#undef CLOUDGRAPH_PLUGIN_ABI_VERSION
#define CLOUDGRAPH_PLUGIN_ABI_VERSION (kEngineAbiVersion + 1)

namespace {

struct RunsAtLoad {
    RunsAtLoad() { ::setenv("CLOUDGRAPH_TEST_PLUGIN_CONSTRUCTOR_RAN", "1", 1); }
};
const RunsAtLoad gRunsAtLoad;

void registerNothing(cg::Registry&) {}

}  // namespace

CLOUDGRAPH_PLUGIN(registerNothing)
