// WriteCamera: the Renderer's camera over the whole shot as a Nuke .chan file.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "algo/render/CameraMatrices.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/ChanFile.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CameraPath.h"
#include "nodes/render/RenderNodes.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

/// The .chan lines of frames first..last.
std::vector<formats::ChanLine> chanLines(const CameraPathData& path, int first, int last)
{
    std::vector<formats::ChanLine> lines;
    for (int frame = first; frame <= last; ++frame) {
        const algo::NukePose pose = algo::nukePose(path.at(frame));
        formats::ChanLine l;
        l.frame = frame;
        for (int a = 0; a < 3; ++a) {
            l.translate[a] = pose.translate[a];
            l.rotateDegrees[a] = pose.rotateDegrees[a];
        }
        l.verticalFovDegrees = pose.verticalFovDegrees;
        lines.push_back(l);
    }
    return lines;
}

class WriteCameraNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto path = ctx.input<CameraPathData>("camera");
        const std::filesystem::path file = ctx.outputPath("file");
        const std::string text =
            formats::chanText(chanLines(*path, ctx.startFrame(), ctx.endFrame()));
        // A moving camera cooks this node on every frame with the same shot.
        if (!util::fileHolds(file, text)) util::writeFileAtomically(file, text);
        ctx.setOutput("files", std::make_shared<TextData>(file.string()));
    }
};

}  // namespace

void registerWriteCameraNode(Registry& registry)
{
    NodeDecl d;
    d.type = "WriteCamera";
    d.category = "io";
    d.doc =
        "Writes the Renderer's camera for every frame of the graph's range as a Nuke .chan "
        "file (ours), which Nuke, Houdini, Maya and Blender's bundled Nuke .chan importer "
        "read: one line a frame, frame, translate x y z, rotate x y z (degrees, order ZXY), "
        "vertical field of view (degrees), in Nuke's y-up world, CloudGraph's (x, y, z) "
        "being (x, z, -y). In Blender, import it with 'Make Z up' and rotation order ZXY "
        "onto a camera whose sensor fits the image. The file holds the whole shot whichever "
        "frames a run cooks, so every run and every farm job writes the same bytes (written "
        "to a temporary name and renamed). See docs/user-guide.md.";
    d.writesFiles = true;
    d.readsFrameRange = true;
    d.inputs = {port("camera", "CameraPath", "the Renderer's camera output")};
    d.outputs = {port("files", "Text", "the path written")};
    d.params = {outputPathParam("file", "camera.chan", "file name, relative to --out")};
    d.create = [] { return std::make_unique<WriteCameraNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
