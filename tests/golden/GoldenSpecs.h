#pragma once
/// The small version of every shipped graph: which parameters shrink it to a few seconds and
/// which frames are recorded. Every graphs/*.json needs an entry (a test checks).

#include <functional>
#include <string>
#include <vector>

namespace cg {
class Graph;
}

namespace cg::golden {

struct GoldenSpec {
    std::string name;                    ///< graphs/<name>.json; also the expected file's name
    std::vector<int> frames;             ///< recorded frames, ascending; the graph ends at the last
    std::function<void(Graph&)> shrink;  ///< the small version, through Graph::setParam
    std::vector<std::string> notCooked;  ///< sinks left out, e.g. EncodeVideo (runs ffmpeg)
};

const std::vector<GoldenSpec>& goldenSpecs();
/// The entry named `name`; nullptr when there is none.
const GoldenSpec* findSpec(const std::string& name);

}  // namespace cg::golden
