#include "core/Plugin.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <exception>
#include <optional>
#include <system_error>

#include <spdlog/spdlog.h>

#include "core/Error.h"

namespace cg {

namespace {

using AbiVersionFn = int (*)();
using RegisterFn = void (*)(Registry*);

InputError abiMismatch(const std::string& where, int version)
{
    return InputError(where, "plugin ABI version " + std::to_string(version) +
                                 ", this cloudgraph needs " +
                                 std::to_string(CLOUDGRAPH_PLUGIN_ABI_VERSION) +
                                 "; rebuild the plugin against this version");
}

/// Whether a symbol from dlsym is code: calling a data symbol would crash the process.
bool isFunction(void* symbol)
{
#if defined(__GLIBC__)  // dladdr1 and RTLD_DL_SYMENT (an enum, not a macro) are glibc's
    Dl_info info{};
    void* raw = nullptr;
    if (dladdr1(symbol, &info, &raw, RTLD_DL_SYMENT) == 0 || !raw) return false;
    const auto* entry = static_cast<const ElfW(Sym)*>(raw);
    const int type = ELF64_ST_TYPE(entry->st_info);
    return type == STT_FUNC || type == STT_GNU_IFUNC;
#else
    (void)symbol;
    return true;
#endif
}

std::string lastDlError()
{
    const char* e = dlerror();
    return e ? e : "unknown error";
}

/// Copies of everything the plugin added to the scratch registry, checked against the real
/// one before any of it is committed.
void commit(const Registry& scratch, Registry& registry)
{
    std::vector<const DataTypeInfo*> newTypes;
    for (const DataTypeInfo* t : scratch.dataTypes()) {
        if (!registry.findDataType(t->name)) newTypes.push_back(t);
    }
    for (const NodeDecl* d : scratch.nodes()) {
        if (registry.findNode(d->type))
            throw std::invalid_argument("node type '" + d->type + "' is registered twice");
    }
    // Nothing below can throw for a name clash; a node's checks only need its data types,
    // which are committed first and already passed in the scratch registry.
    for (const DataTypeInfo* t : newTypes) registry.addDataType(*t);
    for (const NodeDecl* d : scratch.nodes()) registry.addNode(*d);
}

}  // namespace

void loadPlugin(const std::filesystem::path& path, Registry& registry)
{
    const std::string where = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(where, "plugin not found");

    // Absolute, because dlopen searches the library path for a name without a '/'.
    std::filesystem::path file = std::filesystem::absolute(path, ec);
    if (ec || file.empty()) file = path;  // dlopen("") would return the main program
    // The stamp first: dlopen runs the library's static constructors, and those of a plugin
    // built against another engine must not run.
    std::optional<std::int32_t> stamp;
    try {
        stamp = readPluginStampFromFile(file);
    } catch (const std::exception& e) {
        throw InputError(where, std::string("cannot load plugin: ") + e.what());
    }
#if defined(__ELF__)
    if (!stamp)
        throw InputError(where,
                         "not a CloudGraph plugin: no ABI stamp (a plugin is built with "
                         "the CLOUDGRAPH_PLUGIN macro of core/Plugin.h)");
#endif
    if (stamp && *stamp != CLOUDGRAPH_PLUGIN_ABI_VERSION) throw abiMismatch(where, *stamp);

    dlerror();  // clear any stale message
    // RTLD_LOCAL: two plugins may use the same internal symbol names without clashing.
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw InputError(where, "cannot load plugin: " + lastDlError());
    auto entry = [&](const char* name) {
        void* sym = dlsym(handle, name);
        if (!sym || !isFunction(sym)) {
            dlclose(handle);
            throw InputError(where,
                             std::string("not a CloudGraph plugin: ") +
                                 (sym ? "entry point '" + std::string(name) + "' is not a function"
                                      : "missing entry point '" + std::string(name) + "'"));
        }
        return sym;
    };
    // POSIX guarantees a data pointer from dlsym converts to a function pointer.
    auto abiVersion = reinterpret_cast<AbiVersionFn>(entry("cloudgraph_plugin_abi_version"));
    auto registerFn = reinterpret_cast<RegisterFn>(entry("cloudgraph_plugin_register"));
    // Checked again where there is no stamp to read, before any other plugin code runs.
    if (const int version = abiVersion(); version != CLOUDGRAPH_PLUGIN_ABI_VERSION) {
        dlclose(handle);
        throw abiMismatch(where, version);
    }
    // The plugin registers into a scratch registry that knows the current data types, and
    // its additions are committed only when all of them fit: a plugin that fails halfway
    // leaves the registry untouched. The cost: register() sees no existing node types.
    //
    // The handle stays open from here on, even on failure. The plugin's code has run and
    // may have left pointers into itself (statics, loggers); once registered, its code
    // backs the node factories and cooks.
    bool failed = false;
    std::string failure;
    std::vector<std::string> added;
    {
        Registry scratch;
        try {
            for (const DataTypeInfo* t : registry.dataTypes()) scratch.addDataType(*t);
            registerFn(&scratch);
            commit(scratch, registry);
            for (const NodeDecl* d : scratch.nodes()) added.push_back(d->type);
        } catch (const std::exception& e) {
            failed = true;
            failure = e.what();
        } catch (...) {
            failed = true;
            failure = "unknown exception";
        }
    }
    if (failed) throw InputError(where, "plugin failed to register: " + failure);

    std::string list;
    for (const std::string& t : added) list += (list.empty() ? "" : ", ") + t;
    spdlog::info("loaded plugin {}: {}", where, list.empty() ? "no node types" : list);
}

std::vector<std::filesystem::path> pluginsFromSearchPath(const char* searchPath)
{
    namespace fs = std::filesystem;
    std::vector<fs::path> out;
    if (!searchPath) return out;

    const std::string all = searchPath;
    std::size_t start = 0;
    while (start <= all.size()) {
        std::size_t end = all.find(':', start);
        if (end == std::string::npos) end = all.size();
        const std::string entry = all.substr(start, end - start);
        start = end + 1;
        if (entry.empty()) continue;

        const fs::path dir(entry);
        if (!dir.is_absolute()) {
            spdlog::warn("CLOUDGRAPH_PLUGIN_PATH entry '{}' is not absolute; ignored", entry);
            continue;
        }
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) {
            spdlog::warn("CLOUDGRAPH_PLUGIN_PATH directory '{}' does not exist; ignored", entry);
            continue;
        }
        std::vector<fs::path> found;
        fs::directory_iterator it(dir, ec), endIt;
        for (; !ec && it != endIt; it.increment(ec)) {
            std::error_code fileEc;
            if (it->path().extension() == ".so" && it->is_regular_file(fileEc))
                found.push_back(it->path());
        }
        if (ec) spdlog::warn("cannot list plugin directory '{}': {}", entry, ec.message());
        std::sort(found.begin(), found.end());
        out.insert(out.end(), found.begin(), found.end());
    }
    return out;
}

void loadPluginsFromSearchPath(const char* searchPath, Registry& registry)
{
    for (const auto& path : pluginsFromSearchPath(searchPath)) {
        try {
            loadPlugin(path, registry);
        } catch (const InputError& e) {
            spdlog::warn("CLOUDGRAPH_PLUGIN_PATH: skipped {}", e.what());
        }
    }
}

}  // namespace cg
