// EncodeVideo: the PNG frames a WriteImage node wrote, as an H.264 MP4 through ffmpeg.
// It cooks on every frame after the writer (its input) but encodes only on 'lastFrame', when
// every frame of the range is on disk (frames cook in order).

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/VideoEncode.h"
#include "nodes/DeclHelpers.h"
#include "nodes/io/IoNodes.h"
#include "nodes/io/WriterSupport.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

constexpr const char* kProgramName = "ffmpeg";
constexpr const char* kProgramVariable = "CLOUDGRAPH_FFMPEG";

/// The graph's choice only when the user let it choose (load refuses it otherwise), then the
/// environment's, then the fixed name on PATH.
std::string encoderProgram(const std::string& fromGraph)
{
    if (fromGraph != kProgramName) return fromGraph;
    const char* fromEnvironment = std::getenv(kProgramVariable);
    return fromEnvironment && *fromEnvironment ? fromEnvironment : kProgramName;
}

class EncodeVideoNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        const auto last = static_cast<int>(p.getInt("lastFrame"));
        if (ctx.frame() != last) {
            ctx.setOutput("files", std::make_shared<TextData>(""));
            return;
        }
        const auto first = static_cast<int>(p.getInt("firstFrame"));
        formats::VideoEncodeSettings s;
        s.program = encoderProgram(p.getString("ffmpeg"));
        s.firstFrame = first < 0 ? ctx.startFrame() : first;
        s.lastFrame = last;
        // A Retime's files are numbered apart from the frames that write them.
        if (const auto image = static_cast<int>(p.getInt("firstImage")); image >= 0) {
            s.lastFrame = image + (s.lastFrame - s.firstFrame);
            s.firstFrame = image;
        }
        if (const auto image = static_cast<int>(p.getInt("lastImage")); image >= 0)
            s.lastFrame = image;
        s.fps = p.getFloat("fps");
        s.crf = static_cast<int>(p.getInt("crf"));
        const std::string images = p.getString("images");
        if (std::filesystem::path(images).parent_path().string().find('#') != std::string::npos ||
            std::filesystem::path(images).filename().string().find('#') == std::string::npos)
            throw InputError(ctx.nodeId() + "/params/images",
                             "'" + images + "' needs #### (the frame number) in its file name");
        // Resolved under --out as WriteImage resolves its 'file'; #### stays a pattern.
        s.images = framePatternUnderOut(ctx, "images");

        const std::filesystem::path path = ctx.outputPath("file");
        util::AtomicOutput out(path);
        try {
            formats::encodeVideo(s, out.tempPath(), [&ctx] { ctx.checkCancelled(); });
        } catch (const formats::ProgramNotFound& e) {
            throw InputError(ctx.nodeId(),
                             std::string(e.what()) +
                                 ": EncodeVideo needs the ffmpeg program; install it (Debian/"
                                 "Ubuntu: sudo apt-get install -y ffmpeg, or run "
                                 "scripts/install-deps.sh) or set the environment variable " +
                                 std::string(kProgramVariable) + " to its full path");
        }
        out.commit();
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerEncodeVideoNode(Registry& registry)
{
    NodeDecl d;
    d.type = "EncodeVideo";
    d.category = "io";
    d.doc =
        "Encodes the PNG frames written by a WriteImage node into an MP4 video (H.264 by "
        "libx264, yuv420p, playable everywhere; odd sizes padded by one pixel) by running the "
        "ffmpeg program. Cooks on every frame after its input but encodes only on 'lastFrame', "
        "reading frames firstFrame..lastFrame (all must exist), or image files "
        "firstImage..lastImage when they are numbered apart (a Retime's); on other frames "
        "'files' is empty. The video is written beside the target and renamed. Without ffmpeg the "
        "cook "
        "fails with a message saying how to install it. A chunked run (run --chunk) leaves it "
        "out: a farm encodes in its last job, after every chunk is written.";
    d.writesFiles = true;
    d.gathersFrames = true;
    d.frameDependent = true;
    d.inputs = {port("frames", "Text",
                     "the WriteImage node's 'files' output: makes the encoder cook after each "
                     "frame is written")};
    d.outputs = {port("files", "Text", "the video's path on the encoding frame, else empty")};
    d.params = {
        outputPathParam("file", "video.mp4", "the MP4 to write, relative to --out"),
        outputPathParam("images", "image.####.png",
                        "the frames to read: the WriteImage node's 'file' value (relative to "
                        "--out, #### in the file name)"),
        intParam("firstFrame", -1, "frame", "first frame of the video; -1 = the graph's start", -1),
        intParam("lastFrame", 0, "frame",
                 "last frame of the video: the encoder runs when this frame cooks (set it to "
                 "the run's last frame)"),
        intParam("firstImage", -1, "frame",
                 "number of the first image file read, when the files are numbered apart from "
                 "the frames (a Retime's); -1 = firstFrame",
                 -1, 100000000),
        intParam("lastImage", -1, "frame",
                 "number of the last image file read; -1 = firstImage + lastFrame - firstFrame", -1,
                 100000000),
        floatParam("fps", 24.0, "1/s", "frames per second of the video", 1, 240),
        intParam("crf", 18, "",
                 "x264 constant rate factor: 0 lossless, 18 visually lossless, 23 default, 51 "
                 "worst",
                 0, 51),
        programParam("ffmpeg", kProgramName,
                     "the ffmpeg program. Leave it: the node runs $CLOUDGRAPH_FFMPEG, else "
                     "ffmpeg on PATH; a graph that sets it is refused unless run with "
                     "--allow-graph-programs"),
    };
    d.quickParams = {{"lastFrame", "1"}};  // the contract test cooks frame 0: nothing to encode
    d.create = [] { return std::make_unique<EncodeVideoNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
