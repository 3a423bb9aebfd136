#pragma once
/// Plugins: shared libraries that register node types.
///
/// A plugin exports two C functions, best written with CLOUDGRAPH_PLUGIN(fn):
///   int  cloudgraph_plugin_abi_version(void);           must return CLOUDGRAPH_PLUGIN_ABI_VERSION
///   void cloudgraph_plugin_register(cg::Registry*);     adds its node and data types
/// The version is checked before anything else is called, so a plugin built against another
/// engine is refused with a message instead of crashing.

#include <filesystem>
#include <string>
#include <vector>

#include "core/Registry.h"

/// Bump whenever a public engine header changes in a way that breaks compiled plugins.
#define CLOUDGRAPH_PLUGIN_ABI_VERSION 1

#define CLOUDGRAPH_PLUGIN(registerFunction)                                               \
    extern "C" __attribute__((visibility("default"))) int cloudgraph_plugin_abi_version() \
    {                                                                                     \
        return CLOUDGRAPH_PLUGIN_ABI_VERSION;                                             \
    }                                                                                     \
    extern "C" __attribute__((visibility("default"))) void cloudgraph_plugin_register(    \
        cg::Registry* registry)                                                           \
    {                                                                                     \
        registerFunction(*registry);                                                      \
    }

namespace cg {

/// Loads one plugin and registers its nodes. Throws InputError naming the file when it
/// cannot be opened, lacks an entry point, has another ABI version, or fails to register.
/// Registration is all or nothing: the plugin registers into a scratch registry holding the
/// current data types (but no node types), committed only if every addition fits, so a
/// duplicate type leaves `registry` as it was. A plugin whose register function ran is never
/// unloaded, as its code backs the registered nodes; loading the same file into several
/// registries is fine.
void loadPlugin(const std::filesystem::path& path, Registry& registry);

/// Plugin files (*.so) in the directories of CLOUDGRAPH_PLUGIN_PATH (colon-separated).
/// Relative entries are ignored with a warning: plugins never load from the working
/// directory by accident.
std::vector<std::filesystem::path> pluginsFromSearchPath(const char* searchPath);

}  // namespace cg
