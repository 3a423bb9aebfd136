// PrimitiveLoad: a stored primitive-set file (format in formats/PrimitiveFile.h).

#include "core/Error.h"
#include "core/Hash.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/FormatError.h"
#include "formats/PrimitiveFile.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/fluid/FluidNodes.h"

namespace cg {

namespace {

class PrimitiveLoadNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const std::string& file = ctx.params().getString("file");
        if (file.empty())
            throw InputError(ctx.nodeId(), "PrimitiveLoad: parameter 'file' is empty");
        formats::PrimitiveFileReader reader(file);
        std::vector<float> positions = reader.readAll();
        ctx.setOutput("primitive", std::make_shared<PrimitiveSetData>(
                                       reader.frameTime(), reader.counts(), std::move(positions)));
    }
};

}  // namespace

void registerPrimitiveLoadNode(Registry& registry)
{
    NodeDecl d;
    d.type = "PrimitiveLoad";
    d.category = "fluid";
    d.doc =
        "Reads a primitive-set file (.cgp, written by WritePrimitive; format in "
        "docs/primitive.md). Everything is validated: a truncated, altered or foreign file is "
        "refused with the file name and byte offset. The key holds the file's content hash "
        "(XXH3-64 of its bytes), not its path or time stamp.";
    d.outputs = {port("primitive", "PrimitiveSet", "the stored primitive set")};
    d.params = {inputFileParam(
        "file", "", "path of the .cgp file (a relative path is found beside the graph file)")};
    d.hashExtra = [](const ParamSet& p, Hasher& h) {
        // The key holds the file's content, not its path (the engine leaves input-file
        // parameters out), so a copied or moved file is still a cache hit. An unreadable file
        // fails at cook time with its reason; until then its path stands in for the content.
        const std::string& file = p.getString("file");
        try {
            h.str("content").u64(formats::primitiveFileContentHash(file));
        } catch (const formats::FormatError&) {
            h.str("unreadable").str(file);
        }
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        // The header and frame index, so that `validate` refuses a foreign or truncated file;
        // the frames' checksums are checked when they are read.
        const std::string& file = p.getString("file");
        if (file.empty()) return;
        try {
            formats::PrimitiveFileReader reader(file);
        } catch (const formats::FormatError& e) {
            check.fail("file", e.what());
        }
    };
    d.create = [] { return std::make_unique<PrimitiveLoadNode>(); };
    // The contract test has no file to give it; tests/nodes/test_primitive_nodes.cc covers it.
    d.quickParams = {{"__skipCook", "true"}};
    registry.addNode(std::move(d));
}

}  // namespace cg
