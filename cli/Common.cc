#include "cli/Common.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <set>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "core/Error.h"
#include "core/Plugin.h"
#include "formats/FormatError.h"
#include "nodes/Builtin.h"
#include "util/AtomicFile.h"
#include "util/Beneath.h"
#include "util/FramePattern.h"
#ifdef CLOUDGRAPH_WITH_PYTHON
#include "EmbeddedPython.h"
#endif

namespace cg::cli {

namespace {

namespace fs = std::filesystem;

/// Writes a byte into a new file in `out` and removes it: a read-only or full file system is
/// found now instead of at the first write.
void checkWritable(const fs::path& out)
{
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw InputError("--out " + out.string(), "cannot create it: " + ec.message());
    const util::AtomicOutput probe(out / ".write-check");  // never committed: removed
    const int fd = ::open(probe.tempPath().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    int error = fd < 0 ? errno : util::writeAllAt(fd, "x", 1, 0);
    if (fd >= 0 && ::close(fd) != 0 && error == 0) error = errno;
    if (error != 0)
        throw InputError("--out " + out.string(),
                         std::string("cannot write there: ") + std::strerror(error));
}

/// `targets` (the sinks when empty) and every node they read from, directly or not.
std::vector<std::size_t> closureOf(const Graph& graph, const std::vector<std::string>& targets)
{
    std::vector<std::size_t> stack;
    if (targets.empty()) stack = graph.sinks();
    for (const std::string& id : targets) stack.push_back(graph.indexOf(id));
    std::vector<bool> seen(graph.nodes().size(), false);
    std::vector<std::size_t> nodes;
    while (!stack.empty()) {
        const std::size_t idx = stack.back();
        stack.pop_back();
        if (seen[idx]) continue;
        seen[idx] = true;
        nodes.push_back(idx);
        for (std::size_t up : graph.upstream()[idx]) stack.push_back(up);
    }
    return nodes;
}

}  // namespace

void checkOutputPlaces(const Graph& graph, const std::vector<std::string>& targets,
                       FrameRange frames, const fs::path& out)
{
    const bool confined = !graph.limits.allowPathsOutsideOut;
    bool checkedOut = false;
    for (std::size_t idx : closureOf(graph, targets)) {
        const GraphNode& node = graph.nodes()[idx];
        for (std::size_t i = 0; i < node.decl->params.size(); ++i) {
            const ParamDecl& decl = node.decl->params[i];
            if (decl.role != ParamRole::OutputPath) continue;
            const fs::path pattern(std::get<std::string>(node.params.valueAt(i)));
            if (pattern.is_relative() && !checkedOut) {
                checkWritable(out);
                checkedOut = true;
            }
            const auto refuse = [&](const fs::path& file, const std::string& problem) {
                throw InputError(graph.locate(node.pointer + "/params/" + decl.name),
                                 "cannot write '" + file.string() + "': " + problem + " (node '" +
                                     node.id + "')");
            };
            // '#' is only in the file name: one walk finds what is in the way of the
            // directories; the file names of the other frames need one lstat each.
            const bool numbered = util::firstHashRun(pattern.filename().string()).has_value();
            const int last = numbered ? frames.end : frames.start;
            const fs::path first = util::framePath(pattern, frames.start);
            if (confined) {
                if (const std::string problem = util::outputPlaceProblem(out, first);
                    !problem.empty())
                    refuse(out / first, problem);
            }
            for (int frame = frames.start; frame <= last; ++frame) {
                const fs::path file = util::framePath(pattern, frame);
                const fs::path at = file.is_relative() ? out / file : file;
                std::error_code ec;
                if (fs::is_directory(fs::symlink_status(at, ec))) refuse(at, "it is a directory");
            }
        }
    }
}

namespace {

/// The command named `name` in the table; a name missing there is a bug of this program.
const CommandSpec& commandNamed(const std::string& name)
{
    const CommandSpec* command = findCommand(name);
    if (!command) throw std::logic_error("command '" + name + "' is not in the command table");
    return *command;
}

/// One argument: a positional (an empty name), or an option's name and its "--name=value".
struct Token {
    std::string name;
    std::optional<std::string> inlineValue;
};

Token tokenOf(const std::string& a)
{
    if (a.size() < 2 || a[0] != '-' || a == "-") return {};
    if (const auto eq = a.find('='); eq != std::string::npos && a.rfind("--", 0) == 0)
        return {a.substr(0, eq), a.substr(eq + 1)};
    return {a, std::nullopt};
}

}  // namespace

OptionParser::OptionParser(const std::vector<std::string>& args, const std::string& command)
    : mArgs(args), mCommand(commandNamed(command))
{
}

const OptionSpec* OptionParser::find(const std::string& name) const
{
    const std::string wanted = name == "-h" ? "--help" : name;
    for (const auto* list : {&mCommand.options, &commonOptions()})
        for (const OptionSpec& o : *list)
            if (o.name == wanted) return &o;
    return nullptr;
}

bool OptionParser::asksForHelp() const
{
    for (std::size_t i = 0; i < mArgs.size(); ++i) {
        const Token t = tokenOf(mArgs[i]);
        if ((t.name == "--help" || t.name == "-h") && !t.inlineValue) return true;
        const OptionSpec* o = t.name.empty() ? nullptr : find(t.name);
        if (o && !o->value.empty() && !t.inlineValue) ++i;  // skip its value
    }
    return false;
}

void OptionParser::parse()
{
    const std::string seeHelp = " (see cloudgraph " + mCommand.name + " --help)";
    for (std::size_t i = 0; i < mArgs.size(); ++i) {
        const std::string& a = mArgs[i];
        const Token t = tokenOf(a);
        if (t.name.empty()) {
            mPositionals.push_back(a);
            continue;
        }
        const OptionSpec* o = find(t.name);
        if (o && o->value.empty() && !t.inlineValue) {
            mSeen.emplace_back(o->name, "");
        } else if (o && !o->value.empty()) {
            if (t.inlineValue) {
                mSeen.emplace_back(o->name, *t.inlineValue);
            } else if (i + 1 < mArgs.size()) {
                mSeen.emplace_back(o->name, mArgs[++i]);
            } else {
                throw InputError("command line",
                                 "option " + o->name + " needs a value " + o->value + seeHelp);
            }
        } else {
            throw InputError("command line", "unknown option '" + a + "'" + seeHelp);
        }
    }
    if (has("-v")) spdlog::set_level(spdlog::level::debug);
    if (has("-q")) spdlog::set_level(spdlog::level::err);
}

bool OptionParser::has(const std::string& name) const
{
    return std::any_of(mSeen.begin(), mSeen.end(), [&](const auto& s) { return s.first == name; });
}

std::optional<std::string> OptionParser::value(const std::string& name) const
{
    std::optional<std::string> out;
    for (const auto& [n, v] : mSeen)
        if (n == name) out = v;
    return out;
}

std::vector<std::string> OptionParser::values(const std::string& name) const
{
    std::vector<std::string> out;
    for (const auto& [n, v] : mSeen)
        if (n == name) out.push_back(v);
    return out;
}

std::int64_t parseIntegerOption(const std::string& text, const std::string& option,
                                const std::string& what, std::int64_t min, std::int64_t max)
{
    // from_chars: no sign other than '-', no spaces, no trailing text, overflow reported.
    std::int64_t value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || stop != end || value < min || value > max)
        throw InputError(option, "'" + text + "' is not " + what + " between " +
                                     std::to_string(min) + " and " + std::to_string(max));
    return value;
}

void configureLogging()
{
    auto logger = spdlog::stderr_color_mt("cloudgraph");
    logger->set_pattern("%^%l%$: %v");
    spdlog::set_default_logger(logger);
    spdlog::set_level(spdlog::level::info);
}

void buildRegistry(Registry& registry, const OptionParser& opts)
{
    registerBuiltinNodes(registry);
    loadPluginsFromSearchPath(std::getenv("CLOUDGRAPH_PLUGIN_PATH"), registry);
    for (const auto& p : opts.values("--plugin")) loadPlugin(p, registry);
    const std::vector<std::string> pythonFiles = opts.values("--python-nodes");
    if (pythonFiles.empty()) return;
#ifdef CLOUDGRAPH_WITH_PYTHON
    python::loadPythonNodeFiles(pythonFiles, registry);
#else
    throw InputError("--python-nodes",
                     "this cloudgraph was built without Python (pybind11-dev "
                     "and python3-dev, or the sanitizer build)");
#endif
}

LoadOptions graphLoadOptions(const OptionParser& opts)
{
    LoadOptions loadOptions;
    loadOptions.allowPathsOutsideOut = opts.has("--allow-outside-out");
    loadOptions.allowGraphPrograms = opts.has("--allow-graph-programs");
    return loadOptions;
}

namespace {

/// The node.param an override sets ("node.param=value"), or the whole text.
std::string overrideTarget(const std::string& assignment)
{
    return assignment.substr(0, assignment.find('='));
}

/// Applies --set overrides. One that its node's checks across parameters refuse waits until
/// the others are in, so `--set r.cameraPosition=... --set r.cameraLookAt=...` may move a
/// camera in either order; what still fails then is refused with its first error. Of several
/// overrides of one parameter the last wins, as it would in order.
void applySetOverrides(Graph& graph, const std::vector<std::string>& sets)
{
    std::vector<std::string> pending;
    for (std::size_t i = 0; i < sets.size(); ++i) {
        const bool overridden =
            std::any_of(sets.begin() + static_cast<std::ptrdiff_t>(i) + 1, sets.end(),
                        [&](const std::string& later) {
                            return overrideTarget(later) == overrideTarget(sets[i]);
                        });
        if (!overridden) pending.push_back(sets[i]);
    }
    while (!pending.empty()) {
        std::vector<std::string> refused;
        std::exception_ptr first;
        for (const std::string& s : pending) {
            try {
                applySetOverride(graph, s);
            } catch (const InputError&) {
                refused.push_back(s);
                if (!first) first = std::current_exception();
            }
        }
        if (refused.size() == pending.size()) std::rethrow_exception(first);
        pending = std::move(refused);
    }
}

}  // namespace

Graph loadGraphFromOptions(const OptionParser& opts, Registry& registry, const char* command)
{
    if (opts.positionals().size() != 1)
        throw InputError("command line", std::string(command) + " needs exactly one graph file");
    buildRegistry(registry, opts);
    Graph graph = loadGraph(opts.positionals()[0], registry, graphLoadOptions(opts));
    applySetOverrides(graph, opts.values("--set"));
    return graph;
}

int guarded(const std::function<int()>& body)
{
    try {
        return body();
    } catch (const InputError& e) {
        spdlog::error("{}", e.what());
        return kExitBadInput;
    } catch (const formats::FormatError& e) {  // a file read outside any node (`info`)
        spdlog::error("{}", e.what());
        return kExitBadInput;
    } catch (const CookError& e) {
        spdlog::error("{}", e.what());
        return e.inputFault() ? kExitBadInput : kExitFailure;
    } catch (const Cancelled&) {
        spdlog::error("cancelled; nothing partial was cached or written");
        return kExitFailure;
    } catch (const std::exception& e) {
        spdlog::error("internal error: {}", e.what());
        return kExitFailure;
    }
}

}  // namespace cg::cli
