// Retime: a written frame sequence played at another rate, held at its ends and numbered
// from a chosen first frame, without touching the simulation (util/RetimeSchedule.h).

#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/io/IoNodes.h"
#include "nodes/io/WriterSupport.h"
#include "util/AtomicFile.h"
#include "util/FramePattern.h"
#include "util/RetimeSchedule.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

util::RetimeSpec specOf(const CookContext& ctx)
{
    const ParamSet& p = ctx.params();
    util::RetimeSpec s;
    s.first = p.getInt("firstFrame") < 0 ? ctx.startFrame() : p.getInt("firstFrame");
    s.last = ctx.frame();
    s.secondsPerFrame = ctx.timeStep();
    const double rate = p.getFloat("framesPerSecond");
    s.framesPerSecond = rate > 0.0 ? rate : 1.0 / ctx.timeStep();
    s.holdFirst = p.getInt("holdFirst");
    s.holdLast = p.getInt("holdLast");
    return s;
}

/// `target` becomes a copy of `source` in one step: a hard link where the file system has
/// them (a VDB sequence held for a second costs no space), else a copy.
void placeCopy(const fs::path& source, const fs::path& target)
{
    std::error_code ec;
    // Already a link to it (an earlier run): renaming a link onto its twin would do nothing.
    if (fs::equivalent(source, target, ec)) return;
    util::AtomicOutput out(target);
    fs::remove(out.tempPath(), ec);
    fs::create_hard_link(source, out.tempPath(), ec);
    if (ec) fs::copy_file(source, out.tempPath(), fs::copy_options::overwrite_existing);
    out.commit();
}

/// The number of the k-th retimed file (the counts are bounded at load and by the schedule).
int target(std::int64_t first, std::size_t k)
{
    return static_cast<int>(first) + static_cast<int>(k);
}

class RetimeNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        const std::int64_t last =
            p.getInt("lastFrame") < 0 ? ctx.endFrame() : p.getInt("lastFrame");
        if (ctx.frame() != last) {
            ctx.setOutput("files", std::make_shared<TextData>(""));
            return;
        }
        const util::RetimeSpec spec = specOf(ctx);
        if (const std::string problem = util::retimeProblem(spec); !problem.empty())
            throw InputError(ctx.nodeId() + "/params", problem);
        const std::vector<std::int64_t> shows = util::retimeSchedule(spec);
        const fs::path source = framePatternUnderOut(ctx, "source");
        const std::int64_t number =
            p.getInt("numberFrom") < 0 ? spec.first : p.getInt("numberFrom");

        // Every source is there, and no target is one, before anything is written (the
        // target's folder is made only then).
        std::set<fs::path> sources;
        for (std::int64_t f : shows) {
            const fs::path s = util::framePath(source, static_cast<int>(f));
            if (!fs::is_regular_file(s))
                throw InputError(ctx.nodeId() + "/params/source",
                                 "frame file '" + s.string() + "' is missing");
            sources.insert(fs::weakly_canonical(s));
        }
        const fs::path file = framePatternUnderOut(ctx, "file");
        for (std::size_t k = 0; k < shows.size(); ++k)
            if (sources.count(fs::weakly_canonical(util::framePath(file, target(number, k)))))
                throw InputError(ctx.nodeId() + "/params/file",
                                 "the retimed frames would overwrite the frames they show");
        for (std::size_t k = 0; k < shows.size(); ++k) {
            ctx.checkCancelled();
            placeCopy(util::framePath(source, static_cast<int>(shows[k])),
                      util::framePath(file, target(number, k)));
        }
        ctx.setOutput("files", std::make_shared<TextData>(file.string()));
    }
};

void checkPattern(const ParamSet& p, const ParamChecker& check, const char* param)
{
    const std::string& value = p.getString(param);
    if (!util::firstHashRun(fs::path(value).filename().string()))
        check.fail(param, "'" + value + "' needs #### (the frame number) in its file name");
}

}  // namespace

void registerRetimeNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Retime";
    d.category = "io";
    d.doc =
        "Plays the frame files a writer wrote (images, VDBs, point files: any numbered "
        "sequence) at another rate, without changing the simulation or its time step: output "
        "frame j of the retimed run shows the last simulated frame at or before j / "
        "framesPerSecond simulated seconds after firstFrame (a hold, never a blend: a slow "
        "motion repeats frames, a time-lapse skips them). holdFirst frames of the first "
        "frame come before it and holdLast frames of the last after it; the files are "
        "numbered from numberFrom (1001 is the studio convention). It acts when lastFrame "
        "cooks, once every source frame is on disk: it checks that all are there and that "
        "no target is a source before it writes, then places each file in one step (a hard "
        "link where the file system has them, else a copy). With n simulated frames of dt "
        "seconds the shot has holdFirst + floor((n - 1) x dt x framesPerSecond) + 1 + "
        "holdLast frames; an EncodeVideo reads them with firstImage = numberFrom and "
        "lastImage = numberFrom + that count - 1.";
    d.writesFiles = true;
    d.gathersFrames = true;
    d.frameDependent = true;
    d.readsTimeStep = true;
    d.readsFrameRange = true;
    d.inputs = {port("frames", "Text",
                     "the writer's 'files' output: makes the retime cook after each frame is "
                     "written")};
    d.outputs = {
        port("files", "Text", "the retimed files' pattern on the frame it acts, else empty")};
    d.params = {
        outputPathParam("source", "image.####.png",
                        "the frames to read: the writer's 'file' value (relative to --out, "
                        "#### in the file name)"),
        outputPathParam("file", "retimed/image.####.png",
                        "the retimed frames, relative to --out, #### in the file name"),
        intParam("firstFrame", -1, "frame", "first simulated frame shown; -1 = the graph's start",
                 -1),
        intParam("lastFrame", -1, "frame",
                 "last simulated frame shown, and the frame on which the node acts; -1 = the "
                 "graph's end",
                 -1),
        floatParam("framesPerSecond", 0.0, "1/s",
                   "output frames per simulated second; 0 = one per simulated frame (1 / the "
                   "graph's timeStep)",
                   0.0, 1e6),
        intParam("holdFirst", 0, "frames", "frames showing the first frame before the run", 0,
                 util::kMaxRetimedFrames),
        intParam("holdLast", 0, "frames", "frames showing the last frame after the run", 0,
                 util::kMaxRetimedFrames),
        intParam("numberFrom", -1, "frame", "the number of the first retimed file; -1 = firstFrame",
                 -1, 100000000),
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        checkPattern(p, check, "source");
        checkPattern(p, check, "file");
        if (p.getString("source") == p.getString("file"))
            check.fail("file", "the retimed frames need a name other than their source's");
    };
    d.quickParams = {{"__skipCook", "1"}};  // needs a written sequence; tests/nodes cover it
    d.create = [] { return std::make_unique<RetimeNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
