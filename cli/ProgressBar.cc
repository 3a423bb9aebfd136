#include "cli/ProgressBar.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace cg::cli {

ProgressBar::ProgressBar(bool enabled)
    : mEnabled(enabled && ::isatty(STDERR_FILENO)),
      mStart(std::chrono::steady_clock::now()),
      mLastDraw(mStart)
{
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(const Progress& p)
{
    if (!mEnabled || p.total == 0) return;
    std::lock_guard<std::mutex> lock(mMutex);
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - mStart).count();
    if (elapsed < 1.0 || (now - mLastDraw < std::chrono::milliseconds(100) && p.done < p.total))
        return;
    mLastDraw = now;
    const double fraction =
        std::min(1.0, static_cast<double>(p.done) / static_cast<double>(p.total));
    const int width = 30;
    const int filled = static_cast<int>(fraction * width);
    const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %3d%%  frame %d  %zu/%zu  elapsed %.0fs  eta %.0fs   ",
                 bar.c_str(), static_cast<int>(fraction * 100), p.frame, p.done, p.total, elapsed,
                 eta);
    std::fflush(stderr);
    mDrawn = true;
}

void ProgressBar::finish()
{
    std::lock_guard<std::mutex> lock(mMutex);
    if (mDrawn) {
        std::fprintf(stderr, "\r%*s\r", 100, "");
        std::fflush(stderr);
        mDrawn = false;
    }
}

}  // namespace cg::cli
