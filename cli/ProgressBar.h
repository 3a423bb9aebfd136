#pragma once
/// A one-line progress bar with a time estimate, drawn on stderr when it is a terminal and
/// the run has lasted more than a second; silent otherwise.

#include <chrono>
#include <mutex>

#include "core/Evaluator.h"

namespace cg::cli {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled);
    ~ProgressBar();
    void update(const Progress& p);
    /// Clears the line (call before printing anything else).
    void finish();

private:
    bool mEnabled;
    bool mDrawn = false;
    std::mutex mMutex;
    std::chrono::steady_clock::time_point mStart;
    std::chrono::steady_clock::time_point mLastDraw;
};

}  // namespace cg::cli
