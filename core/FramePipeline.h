#pragma once
/// Frames cooked as a pipeline: a node cooks at frame f as soon as its inputs at f and the
/// node itself at f − 1 are done, with up to `window` frames in flight. Each node cooks its
/// frames in order (simulations step forward, writers write in order), unless it is one of
/// the `anyOrder` nodes, which need not wait for their frame before; one frame's last nodes
/// (image writers, encoders, often serial) run beside the next frame's first ones instead of
/// leaving cores idle. Nodes are indices of a graph; what cooking one means is the caller's
/// (Evaluator).

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "core/MemoryCache.h"

namespace cg {

class FramePipeline {
public:
    using FrameOutputs = std::vector<OutputsPtr>;
    /// The nodes to cook at `frame`, in topological order. It may fill `results` for nodes
    /// it settles without cooking (writers whose files verify); those are not cooked.
    using Plan = std::function<std::vector<std::size_t>(int frame, FrameOutputs& results)>;
    /// Cooks node `idx` at `frame`; its inputs are in `results`.
    using Cook = std::function<OutputsPtr(std::size_t idx, int frame, const FrameOutputs& results)>;
    /// Called once per frame, in frame order, one at a time, when all its nodes are done.
    using Done = std::function<void(int frame, const FrameOutputs& results)>;

    /// `upstream[i]`: the nodes node i reads. `anyOrder[i]` (all false if empty): node i may
    /// cook a frame while it still cooks the frame before.
    FramePipeline(const std::vector<std::vector<std::size_t>>& upstream, int window,
                  std::vector<bool> anyOrder = {});

    /// Cooks frames first..last. A cook that throws at frame f stops every cook at f or
    /// later that has not started (those under way finish); the frames before f finish. The
    /// exception of the earliest frame that failed is rethrown here. A frame after f may
    /// have cooked some nodes (and written their files) by then.
    void run(int first, int last, const Plan& plan, const Cook& cook, const Done& done);

private:
    const std::vector<std::vector<std::size_t>>& mUpstream;
    std::vector<std::vector<std::size_t>> mDownstream;
    std::vector<bool> mInOrder;  ///< per node: waits for its own frame before
    int mWindow;
};

}  // namespace cg
