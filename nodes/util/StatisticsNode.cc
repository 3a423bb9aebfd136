// Statistics: mean, min, max and count of a FloatArray, plus a one-line summary.

#include <algorithm>
#include <cstdio>
#include <limits>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

namespace {

class StatisticsNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto in = ctx.input<FloatArrayData>("values");
        const std::vector<float>& v = in->values;
        // Summed in double, in index order, so the result never depends on thread count.
        double sum = 0.0;
        double lo = std::numeric_limits<double>::quiet_NaN();
        double hi = lo;
        if (!v.empty()) lo = hi = v[0];
        for (float x : v) {
            sum += x;
            lo = std::min<double>(lo, x);
            hi = std::max<double>(hi, x);
        }
        const double mean = v.empty() ? std::numeric_limits<double>::quiet_NaN()
                                      : sum / static_cast<double>(v.size());
        char line[160];
        std::snprintf(line, sizeof line, "frame %d: count %zu mean %.9g min %.9g max %.9g\n",
                      ctx.frame(), v.size(), mean, lo, hi);
        ctx.setOutput("mean", std::make_shared<FloatData>(mean));
        ctx.setOutput("min", std::make_shared<FloatData>(lo));
        ctx.setOutput("max", std::make_shared<FloatData>(hi));
        ctx.setOutput("count", std::make_shared<IntData>(static_cast<std::int64_t>(v.size())));
        ctx.setOutput("summary", std::make_shared<TextData>(line));
    }
};

}  // namespace

void registerStatisticsNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Statistics";
    d.category = "util";
    d.doc =
        "Mean, minimum, maximum and count of an array (NaN for an empty one), and a "
        "one-line text summary that names the frame.";
    d.frameDependent = true;  // the summary names the frame
    d.inputs = {port("values", "FloatArray", "the values to summarise")};
    d.outputs = {port("mean", "Float", "arithmetic mean"), port("min", "Float", "smallest value"),
                 port("max", "Float", "largest value"), port("count", "Int", "number of values"),
                 port("summary", "Text", "\"frame F: count N mean M min A max B\"")};
    d.create = [] { return std::make_unique<StatisticsNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
