#pragma once
/// Which simulated frame each frame of a retimed shot shows. A shot plays the simulated
/// frames first..last (each `secondsPerFrame` of simulated time) at `framesPerSecond` output
/// frames per simulated second, after `holdFirst` frames that show `first` and before
/// `holdLast` frames that show `last`. An output frame shows the last simulated frame at or
/// before its time: a hold, never a blend (slow motion repeats frames, a time-lapse skips them).

#include <cstdint>
#include <string>
#include <vector>

namespace cg::util {

struct RetimeSpec {
    std::int64_t first = 0;        ///< simulated frames first..last
    std::int64_t last = 0;         ///< >= first
    double secondsPerFrame = 1.0;  ///< of the simulation (the graph's time step), > 0
    double framesPerSecond = 1.0;  ///< output frames per simulated second, > 0
    std::int64_t holdFirst = 0;    ///< >= 0
    std::int64_t holdLast = 0;     ///< >= 0
};

/// The most frames a retimed shot may have (the graph format's frame limit).
constexpr std::int64_t kMaxRetimedFrames = 1000000;

/// How many frames the shot has, or -1 when the spec is unusable or the count exceeds
/// kMaxRetimedFrames (computed without building the list).
std::int64_t retimedFrameCount(const RetimeSpec& spec);

/// Why the spec cannot be retimed, or empty when it can.
std::string retimeProblem(const RetimeSpec& spec);

/// The simulated frame each output frame shows, in output order (retimeProblem empty).
std::vector<std::int64_t> retimeSchedule(const RetimeSpec& spec);

}  // namespace cg::util
