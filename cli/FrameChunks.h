#pragma once
/// Splitting a frame range into chunks for a render farm: chunk I of N frames each, the
/// last chunk clamped to the range. The task index comes from --task or, on a Slurm job
/// array, from SLURM_ARRAY_TASK_ID.

#include <optional>
#include <string>

#include "core/Graph.h"

namespace cg::cli {

/// --frames A:B (or A), inside the graph's range; InputError naming --frames otherwise.
FrameRange parseFrameRange(const std::string& text, const FrameRange& graphRange);

/// --chunk N: a positive frame count; InputError naming --chunk otherwise.
int parseChunkSize(const std::string& text);

/// How many chunks of `chunkSize` frames cover `range`.
int chunkCount(const FrameRange& range, int chunkSize);

/// The frames of chunk `task`. `taskText` is --task's value or, when absent,
/// SLURM_ARRAY_TASK_ID's. Throws InputError naming the option or variable that is
/// missing, not a number, or past the last chunk.
FrameRange chunkFrames(const FrameRange& range, int chunkSize,
                       const std::optional<std::string>& taskText,
                       const std::optional<std::string>& slurmTaskId);

}  // namespace cg::cli
