// ReadMap: a painted image (PNG, PFM or OpenEXR) as a Map2D.

#include <algorithm>
#include <memory>
#include <string>

#include "core/Error.h"
#include "core/Hash.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/FileHash.h"
#include "formats/FormatError.h"
#include "formats/MapFile.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/Map2D.h"
#include "nodes/io/IoNodes.h"
#include "util/SystemMemory.h"

namespace cg {

namespace {

/// The file's values as a map's: refused outside [0, 1], or clamped into it.
formats::MapImage readMapValues(const ParamSet& p, std::uint64_t allocationLimitBytes)
{
    formats::MapImage map =
        formats::readMapFile(p.getString("file"), allocationLimitBytes / sizeof(float));
    const bool clamp = p.getString("outOfRange") == "clamp";
    for (std::size_t i = 0; i < map.values.size(); ++i) {
        float& v = map.values[i];
        if (v >= 0.0f && v <= 1.0f) continue;
        if (!clamp)
            throw formats::FormatError(
                p.getString("file"),
                "cell (" + std::to_string(i % static_cast<std::size_t>(map.nx)) + ", " +
                    std::to_string(i / static_cast<std::size_t>(map.nx)) + ") is " +
                    std::to_string(v) + ", outside a map's [0, 1] (outOfRange 'clamp' clamps it)");
        v = std::clamp(v, 0.0f, 1.0f);
    }
    return map;
}

class ReadMapNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        formats::MapImage map = readMapValues(ctx.params(), util::nodeAllocationLimitBytes());
        ctx.setOutput("map",
                      std::make_shared<Map2DData>(map.nx, map.ny, ctx.params().getFloat("cellSize"),
                                                  std::move(map.values)));
    }
};

}  // namespace

void registerReadMapNode(Registry& registry)
{
    NodeDecl d;
    d.type = "ReadMap";
    d.category = "io";
    d.doc =
        "Reads a painted map (ours): a greyscale or RGB PNG of 8 or 16 bits, a greyscale PFM or "
        "an OpenEXR image (told apart by their first bytes) as a Map2D of cellSize-metre cells, "
        "one a pixel. The image's bottom row is the map's row iy = 0 and its left column ix = "
        "0, so the map lies on the ground as the painting shows it from above with +y up "
        "(WriteMap's orientation: a WriteMap PFM reads back bit for bit). PNG samples become "
        "q / 255 or q / 65535; RGB images their Rec. 709 luminance of the stored values; an "
        "EXR's Y channel as it is. Values outside [0, 1] are refused (outOfRange 'clamp' clamps "
        "them). The key holds the file's content, not its path. Refused with the file named "
        "(exit 2): another format, an alpha or palette PNG, more than 16384 pixels a side or "
        "more than one node may allocate (checked before the pixels are read), a value that "
        "is not finite.";
    d.outputs = {port("map", "Map2D", "the painted map, values in [0, 1]")};
    d.params = {
        inputFileParam("file", "", "the image (a relative path is found beside the graph file)"),
        floatParam("cellSize", 50.0, "m", "ground size of one pixel (NoiseMap's default)", 0.001,
                   1e6),
        stringParam("outOfRange", "refuse",
                    "what a value outside [0, 1] does: refuse (an error naming the cell) or "
                    "clamp",
                    {"refuse", "clamp"}),
    };
    d.hashExtra = [](const ParamSet& p, Hasher& h) {
        const std::string& file = p.getString("file");
        try {
            h.str("content").u64(
                formats::fileContentHash(file, util::nodeAllocationLimitBytes(), "map image"));
        } catch (const formats::FormatError&) {
            h.str("unreadable").str(file);
        }
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        if (p.getString("file").empty()) return;  // refused when cooked, naming the file
        try {
            readMapValues(p, check.allocationLimitBytes);
        } catch (const formats::FormatError& e) {
            check.fail("file", e.what());
        }
    };
    d.create = [] { return std::make_unique<ReadMapNode>(); };
    // The contract test has no image to give it; tests/nodes/test_map_nodes.cc covers it.
    d.quickParams = {{"__skipCook", "true"}};
    registry.addNode(std::move(d));
}

}  // namespace cg
