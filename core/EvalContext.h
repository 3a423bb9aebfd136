#pragma once
/// What a cook may know of the evaluation beyond its parameters and inputs.

#include <atomic>
#include <cstdint>
#include <memory>

#include "core/Error.h"

namespace cg {

/// Cooperative cancellation: set from anywhere (a signal handler, another thread); nodes
/// call CookContext::checkCancelled() in their loops, which throws Cancelled.
class CancelToken {
public:
    void cancel() { mCancelled.store(true, std::memory_order_relaxed); }
    bool cancelled() const { return mCancelled.load(std::memory_order_relaxed); }
    void throwIfCancelled() const
    {
        if (cancelled()) throw Cancelled();
    }

private:
    std::atomic<bool> mCancelled{false};
};

struct EvalContext {
    int frame = 0;
    int startFrame = 0;      ///< simulations start here (the graph's first frame)
    int endFrame = 0;        ///< the graph's last frame
    double timeStep = 1.0;   ///< seconds per frame
    std::uint64_t seed = 0;  ///< the graph's global seed
    /// Output paths may leave the output directory (--allow-outside-out): then they are not
    /// resolved beneath it either, and a symbolic link in it is followed where it leads.
    bool allowOutsideOut = false;
    std::shared_ptr<CancelToken> cancel = std::make_shared<CancelToken>();
};

}  // namespace cg
