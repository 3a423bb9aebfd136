// WriteArray and WriteText: write a value per frame to a file under the output directory.

#include <cstdio>
#include <string>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/util/UtilNodes.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

class WriteArrayNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto in = ctx.input<FloatArrayData>("values");
        std::string text;
        text.reserve(in->values.size() * 12);
        char buf[32];
        for (std::size_t i = 0; i < in->values.size(); ++i) {
            if ((i & 0xffff) == 0) ctx.checkCancelled();
            // %.9g round-trips every float exactly.
            const int n =
                std::snprintf(buf, sizeof buf, "%.9g\n", static_cast<double>(in->values[i]));
            text.append(buf, static_cast<std::size_t>(n));
        }
        const auto path = ctx.outputPath("file");
        util::writeFileAtomically(path, text);
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

class WriteTextNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto in = ctx.input<TextData>("text");
        const auto path = ctx.outputPath("file");
        util::writeFileAtomically(path, in->value);
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWriterNodes(Registry& registry)
{
    NodeDecl array = writerDecl(
        "WriteArray",
        "Writes an array as text, one value per line (%.9g, exact for float32), to a file "
        "under the output directory; #### in the name becomes the frame number.",
        port("values", "FloatArray", "values to write"), "values.####.txt");
    array.create = [] { return std::make_unique<WriteArrayNode>(); };
    registry.addNode(std::move(array));

    NodeDecl text = writerDecl("WriteText",
                               "Writes text to a file under the output directory; #### in the "
                               "name becomes the frame number.",
                               port("text", "Text", "text to write"), "summary.####.txt");
    text.create = [] { return std::make_unique<WriteTextNode>(); };
    registry.addNode(std::move(text));
}

}  // namespace cg
