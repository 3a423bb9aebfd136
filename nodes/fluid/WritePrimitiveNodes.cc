// WritePrimitive (the .cgp file) and WritePrimitivePly (a frame range as PLY point clouds).

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/PrimitiveFile.h"
#include "formats/PrimitivePly.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/fluid/FluidNodes.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

class WritePrimitiveNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto prim = ctx.input<PrimitiveSetData>("primitive");
        const auto path = ctx.outputPath("file");
        formats::writePrimitiveFile(path, prim->frameTime, prim->counts, prim->positions);
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

class WritePrimitivePlyNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto prim = ctx.input<PrimitiveSetData>("primitive");
        const auto first = static_cast<int>(ctx.params().getInt("first"));
        auto last = static_cast<int>(ctx.params().getInt("last"));
        const auto every = static_cast<int>(ctx.params().getInt("every"));
        if (last < 0 || last >= prim->frames()) last = prim->frames() - 1;
        if (first > last)
            throw InputError(ctx.nodeId(), "first frame " + std::to_string(first) +
                                               " is after the last, " + std::to_string(last));
        const auto pattern = ctx.outputPath("file");
        std::string written;
        for (int s = first; s <= last; s += every) {
            const auto path = formats::primitiveFramePath(pattern, s);
            util::AtomicOutput out(path);
            formats::writePrimitiveFramePly(out.tempPath(), prim->frame(s), prim->count(s), s,
                                            [&ctx] { ctx.checkCancelled(); });
            out.commit();
            written += (written.empty() ? "" : "\n") + path.string();
        }
        ctx.setOutput("files", std::make_shared<TextData>(written));
    }
};

NodeDecl writer(std::string type, std::string doc, std::string file)
{
    NodeDecl d;
    d.type = std::move(type);
    d.category = "io";
    d.doc = std::move(doc);
    d.writesFiles = true;
    d.inputs = {port("primitive", "PrimitiveSet", "the primitive set to write")};
    d.outputs = {port("files", "Text", "the paths written, one per line")};
    d.params = {outputPathParam("file", std::move(file), "file name, relative to --out")};
    return d;
}

}  // namespace

void registerWritePrimitiveNodes(Registry& registry)
{
    NodeDecl d = writer("WritePrimitive",
                        "Writes a primitive set to a .cgp file (format in docs/primitive.md): "
                        "header, frame index, one checksummed block per frame; atomic (temporary "
                        "file, then rename). `cloudgraph info FILE` summarises it; PrimitiveLoad "
                        "reads it back.",
                        "primitive.cgp");
    d.create = [] { return std::make_unique<WritePrimitiveNode>(); };
    registry.addNode(std::move(d));

    NodeDecl p = writer("WritePrimitivePly",
                        "Writes frames first..last (every `every`-th) of a primitive set as binary "
                        "PLY point clouds, one file per frame: '.ssss' (frame s, zero-padded) "
                        "goes before the extension (do not use ####: the engine fills it with "
                        "the evaluation frame). Properties "
                        "x y z (m, from the cloud origin), id (stable), state 1.",
                        "primitive/frame.ply");
    p.params.push_back(intParam("first", 0, "frames", "first primitive frame s to write", 0, 1e7));
    p.params.push_back(
        intParam("last", -1, "frames", "last frame s to write; -1 = the last frame", -1, 1e7));
    p.params.push_back(
        intParam("every", 1, "frames", "write every Nth frame from `first`", 1, 1e7));
    p.create = [] { return std::make_unique<WritePrimitivePlyNode>(); };
    registry.addNode(std::move(p));
}

}  // namespace cg
