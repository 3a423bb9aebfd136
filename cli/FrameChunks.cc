#include "cli/FrameChunks.h"

#include <algorithm>

#include "cli/Common.h"
#include "core/Error.h"

namespace cg::cli {

namespace {

/// Far more frames than any animation has; keeps chunk arithmetic in int.
constexpr std::int64_t kMaxChunk = std::int64_t{1} << 24;

}  // namespace

FrameRange parseFrameRange(const std::string& text, const FrameRange& graphRange)
{
    const auto colon = text.find(':');
    auto frame = [&](const std::string& part) {
        return static_cast<int>(
            parseIntegerOption(part, "--frames", "a frame", graphRange.start, graphRange.end));
    };
    FrameRange r;
    r.start = frame(text.substr(0, colon));
    r.end = colon == std::string::npos ? r.start : frame(text.substr(colon + 1));
    if (r.end < r.start) {
        throw InputError("--frames", "range " + text + " is not inside the graph's frames " +
                                         std::to_string(graphRange.start) + ":" +
                                         std::to_string(graphRange.end));
    }
    return r;
}

int parseChunkSize(const std::string& text)
{
    return static_cast<int>(parseIntegerOption(text, "--chunk", "a frame count", 1, kMaxChunk));
}

int chunkCount(const FrameRange& range, int chunkSize)
{
    const std::int64_t frames = std::int64_t{range.end} - range.start + 1;
    return static_cast<int>((frames + chunkSize - 1) / chunkSize);
}

FrameRange chunkFrames(const FrameRange& range, int chunk,
                       const std::optional<std::string>& taskText,
                       const std::optional<std::string>& slurmTaskId)
{
    const int chunks = chunkCount(range, chunk);
    const std::string source = taskText ? "--task" : "SLURM_ARRAY_TASK_ID";
    const std::optional<std::string>& text = taskText ? taskText : slurmTaskId;
    if (!text) {
        throw InputError("--task",
                         "--chunk needs a task index: give --task I or run as a Slurm "
                         "array task (SLURM_ARRAY_TASK_ID)");
    }
    const std::int64_t task = parseIntegerOption(*text, source, "a chunk index", 0, chunks - 1);
    FrameRange r;
    r.start = static_cast<int>(range.start + task * chunk);
    r.end = static_cast<int>(std::min<std::int64_t>(range.end, std::int64_t{r.start} + chunk - 1));
    return r;
}

}  // namespace cg::cli
