#pragma once
/// Plugins: shared libraries that register node types.
///
/// A plugin is made with CLOUDGRAPH_PLUGIN(fn), which gives it
///   - an ABI stamp (PluginStamp.h) in its file, read before the library is loaded, so a
///     plugin built against another engine is refused before any of its code runs (dlopen
///     would run its static constructors);
///   - int  cloudgraph_plugin_abi_version(void), the same version, for platforms without ELF;
///   - void cloudgraph_plugin_register(cg::Registry*), which adds its node and data types.
/// Both entry points must be functions: a library whose entry symbols are data is refused.

#include <filesystem>
#include <string>
#include <vector>

#include "core/PluginStamp.h"
#include "core/Registry.h"

/// Bump whenever a public engine header changes in a way that breaks compiled plugins.
#define CLOUDGRAPH_PLUGIN_ABI_VERSION 1

#define CLOUDGRAPH_PLUGIN(registerFunction)                                                \
    extern "C" __attribute__((visibility("default"), used, section(".cloudgraph_plugin"))) \
    const cg::PluginStamp cloudgraph_plugin_stamp = {"CloudGraphPlugn",                    \
                                                     CLOUDGRAPH_PLUGIN_ABI_VERSION};       \
    extern "C" __attribute__((visibility("default"))) int cloudgraph_plugin_abi_version()  \
    {                                                                                      \
        return CLOUDGRAPH_PLUGIN_ABI_VERSION;                                              \
    }                                                                                      \
    extern "C" __attribute__((visibility("default"))) void cloudgraph_plugin_register(     \
        cg::Registry* registry)                                                            \
    {                                                                                      \
        registerFunction(*registry);                                                       \
    }

namespace cg {

/// Loads one plugin and registers its nodes. Throws InputError naming the file when it
/// cannot be opened, is not a plugin (no stamp, entry points missing or not functions), has
/// another ABI version, or fails to register.
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

/// Loads every plugin of the search path; one that is refused is reported as a warning and
/// skipped, so a bad library in a shared directory does not stop every command.
void loadPluginsFromSearchPath(const char* searchPath, Registry& registry);

}  // namespace cg
