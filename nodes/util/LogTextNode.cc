// LogText: prints a text value in the run's log on chosen frames, e.g. the mapper's
// per-level counts on the frames a graph writes.

#include <string>

#include <spdlog/spdlog.h>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

namespace {

class LogTextNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto every = ctx.params().getInt("every");
        const bool logs = (ctx.frame() - ctx.startFrame()) % every == 0;
        std::string line;
        if (logs) {
            line = ctx.input<TextData>("text")->value;
            while (!line.empty() && line.back() == '\n') line.pop_back();
            spdlog::info("{}: {}", ctx.nodeId(), line);
        }
        // The logged line is also this node's output, so the run report keeps it.
        ctx.setOutput("logged", std::make_shared<TextData>(line));
    }
};

}  // namespace

void registerLogTextNode(Registry& registry)
{
    NodeDecl d;
    d.type = "LogText";
    d.category = "util";
    d.doc =
        "Prints its text in the run's log (info level, prefixed with the node id) on frames "
        "start, start + every, ...; the printed line is also its output, so the run report "
        "(--report) records it. Cooks on every run, like a writer, so a cached graph still "
        "prints.";
    d.writesFiles = true;
    d.frameDependent = true;
    d.inputs = {port("text", "Text", "the text to print")};
    d.outputs = {
        port("logged", "Text", "the line printed at this frame (empty on skipped frames)")};
    d.params = {intParam("every", 1, "frames", "print every this many frames from the start", 1)};
    d.create = [] { return std::make_unique<LogTextNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
