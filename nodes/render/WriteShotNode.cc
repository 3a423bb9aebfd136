// WriteShot: the shot as JSON (camera per frame, sun, sky, ground, the cloud's optics) for
// another renderer to match CloudGraph's (the Blender add-on reads it).

#include <memory>
#include <string>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CameraPath.h"
#include "nodes/render/RenderNodes.h"
#include "nodes/render/ShotJson.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

class WriteShotNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto camera = ctx.input<CameraPathData>("camera");
        const auto lighting = ctx.input<TextData>("lighting");
        const std::filesystem::path file = ctx.outputPath("file");
        const std::string text =
            shotJson(*camera, ctx.startFrame(), ctx.endFrame(), ctx.timeStep(), lighting->value);
        if (!util::fileHolds(file, text)) util::writeFileAtomically(file, text);
        ctx.setOutput("files", std::make_shared<TextData>(file.string()));
    }
};

}  // namespace

void registerWriteShotNode(Registry& registry)
{
    NodeDecl d;
    d.type = "WriteShot";
    d.category = "io";
    d.doc =
        "Writes the shot as JSON (ours, 'cloudgraph_shot' version 1) for another renderer to "
        "frame and light CloudGraph's VDBs as the Renderer does: the graph's frame range and "
        "frame time (timeStep), the image size, the camera of every frame (position, look-at, "
        "up, vertical field of view), the sun (unit direction toward it, colour, irradiance), "
        "the sky gradient, the ground and the medium (extinction per unit of the grid, albedo, "
        "phase) after the volume's optics metadata replaced the parameters. Metres, z up, "
        "linear Rec.709. The file holds the whole shot whichever frames a run cooks (written "
        "to a temporary name and renamed). The Blender add-on "
        "(integrations/blender) imports it with the VDBs.";
    d.writesFiles = true;
    d.readsFrameRange = true;
    d.readsTimeStep = true;
    d.inputs = {port("camera", "CameraPath", "the Renderer's camera output"),
                port("lighting", "Text", "the Renderer's lighting output")};
    d.outputs = {port("files", "Text", "the path written")};
    d.params = {outputPathParam("file", "shot.json", "file name, relative to --out")};
    // Needs the Renderer's lighting JSON; tests/nodes/test_camera_moves.cc covers it.
    d.quickParams = {{"__skipCook", "true"}};
    d.create = [] { return std::make_unique<WriteShotNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
