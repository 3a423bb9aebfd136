// WriteMap: a Map2D as a float PFM plus a 16-bit PNG preview beside it.

#include <cctype>
#include <filesystem>
#include <memory>
#include <string>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/MapImage.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/Map2D.h"
#include "nodes/io/IoNodes.h"
#include "nodes/io/WriterSupport.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

/// The preview's name: a .pfm extension becomes .png; any other name gets .png appended, so
/// "map.####" (whose extension is the frame number) or "map.png" never collide.
std::filesystem::path previewPath(std::filesystem::path pfm)
{
    std::string ext = pfm.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".pfm") return pfm.replace_extension(".png");
    pfm += ".png";
    return pfm;
}

class WriteMapNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto map = ctx.input<Map2DData>("map");
        const std::filesystem::path pfmPath = ctx.outputPath("file");
        const std::filesystem::path pngPath = previewPath(pfmPath);

        // Both files are written in full before either is committed.
        util::AtomicOutput pfm(pfmPath);
        util::AtomicOutput png(pngPath);
        formats::writePfm(pfm.tempPath().string(), map->nx, map->ny, map->values);
        ctx.checkCancelled();
        formats::writePng16(png.tempPath().string(), map->nx, map->ny, map->values);
        ctx.checkCancelled();
        pfm.commit();
        png.commit();
        ctx.setOutput("files",
                      std::make_shared<TextData>(pfmPath.string() + "\n" + pngPath.string()));
    }
};

}  // namespace

void registerWriteMapNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteMap",
        "Writes a Map2D as a greyscale PFM (float32, exact values) and a 16-bit greyscale PNG "
        "preview beside it (values in [0, 1] to 0..65535, clamped; name: .pfm replaced by "
        ".png, else .png appended). Both images show +y up: the map's row iy = 0 is the "
        "bottom row. #### in the name becomes the frame number; both files appear atomically.",
        port("map", "Map2D", "the map to write"), "map.####.pfm");
    d.outputs = {port("files", "Text", "the PFM path and the PNG path, separated by a newline")};
    d.create = [] { return std::make_unique<WriteMapNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
