#include "nodes/io/WriterSupport.h"

#include <algorithm>
#include <cstdint>

#include "nodes/DeclHelpers.h"

namespace cg {

std::filesystem::path framePatternUnderOut(const CookContext& ctx, const std::string& param)
{
    return ctx.outputPath(param).parent_path() /
           std::filesystem::path(ctx.params().getString(param)).filename();
}

int scheduledFrames(std::int64_t first, std::int64_t every, std::int64_t start, std::int64_t end)
{
    if (first < start) first += (start - first + every - 1) / every * every;
    if (first > end) return 0;
    return 1 + static_cast<int>(std::min<std::int64_t>(1, (end - first) / every));
}

void addSequenceParams(NodeDecl& d)
{
    for (auto& p : d.params)
        if (p.name == "every")
            p.doc = "write frames firstFrame, firstFrame + every, ...; skip the rest";
    d.params.push_back(
        intParam("firstFrame", -1, "frame",
                 "first frame to write, from which 'every' counts; -1 = the graph's start", -1));
    d.params.push_back(boolParam("skipEmpty", true,
                                 "write no file for an empty frame (e.g. before the cloud forms)"));
    // The frames writesSequenceFrame schedules (skipEmpty aside: any may hold something).
    d.framesWritten = [](const ParamSet& p, int start, int end) {
        const std::int64_t first = p.getInt("firstFrame");
        return scheduledFrames(first < 0 ? start : first, p.getInt("every"), start, end);
    };
    d.idleOnFrame = [](const ParamSet& p, int frame, int start) {
        const std::int64_t first = p.getInt("firstFrame");
        return !scheduledFrame(first < 0 ? start : first, p.getInt("every"), frame);
    };
}

bool writesSequenceFrame(CookContext& ctx, bool empty)
{
    const auto& p = ctx.params();
    const auto first = p.getInt("firstFrame") < 0 ? ctx.startFrame() : p.getInt("firstFrame");
    if (scheduledFrame(first, p.getInt("every"), ctx.frame()) && !(empty && p.getBool("skipEmpty")))
        return true;
    ctx.setOutput("files", std::make_shared<TextData>(""));
    return false;
}

}  // namespace cg
