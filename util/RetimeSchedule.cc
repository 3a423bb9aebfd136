#include "util/RetimeSchedule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cg::util {

namespace {

/// Output frames per simulated frame.
double outputPerSimulated(const RetimeSpec& s) { return s.framesPerSecond * s.secondsPerFrame; }

/// Frames of the retimed run between the holds: the output frames whose time falls within
/// the simulated span, the first showing `first`. The tolerance keeps a rate that divides
/// the span from losing its last frame to rounding.
double retimedSpan(const RetimeSpec& s)
{
    return std::floor(static_cast<double>(s.last - s.first) * outputPerSimulated(s) + 1e-9) + 1.0;
}

}  // namespace

std::string retimeProblem(const RetimeSpec& s)
{
    if (s.last < s.first) return "the last frame comes before the first";
    if (!(s.secondsPerFrame > 0.0) || !std::isfinite(s.secondsPerFrame))
        return "the simulated seconds per frame must be > 0";
    if (!(s.framesPerSecond > 0.0) || !std::isfinite(s.framesPerSecond))
        return "the frames per simulated second must be > 0";
    if (s.holdFirst < 0 || s.holdLast < 0) return "a hold must be >= 0 frames";
    const double count =
        retimedSpan(s) + static_cast<double>(s.holdFirst) + static_cast<double>(s.holdLast);
    if (!(count <= static_cast<double>(kMaxRetimedFrames)))
        return "the shot would have " + std::to_string(count) + " frames, more than " +
               std::to_string(kMaxRetimedFrames);
    return {};
}

std::int64_t retimedFrameCount(const RetimeSpec& s)
{
    if (!retimeProblem(s).empty()) return -1;
    return static_cast<std::int64_t>(retimedSpan(s)) + s.holdFirst + s.holdLast;
}

std::vector<std::int64_t> retimeSchedule(const RetimeSpec& s)
{
    if (const std::string problem = retimeProblem(s); !problem.empty())
        throw std::invalid_argument("retime: " + problem);
    std::vector<std::int64_t> shows(static_cast<std::size_t>(s.holdFirst), s.first);
    const auto span = static_cast<std::int64_t>(retimedSpan(s));
    const double perSimulated = outputPerSimulated(s);
    for (std::int64_t j = 0; j < span; ++j) {
        // Output frame j is at j / perSimulated simulated frames after `first`.
        const auto step =
            static_cast<std::int64_t>(std::floor(static_cast<double>(j) / perSimulated + 1e-9));
        shows.push_back(std::min(s.first + step, s.last));
    }
    shows.insert(shows.end(), static_cast<std::size_t>(s.holdLast), s.last);
    return shows;
}

}  // namespace cg::util
