#pragma once
/// What every writer node shares.

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/NodeDecl.h"

namespace cg {

/// Whether a writer scheduled on frames first, first + every, ... writes on `frame`.
inline bool scheduledFrame(std::int64_t first, std::int64_t every, std::int64_t frame)
{
    return frame >= first && (frame - first) % every == 0;
}

/// How many of the frames start..end that schedule holds, counted to 2 (NodeDecl's
/// framesWritten: "several" is all a load-time check needs).
int scheduledFrames(std::int64_t first, std::int64_t every, std::int64_t start, std::int64_t end);

/// True on the frames a writer declared with writerDecl writes: start, start + every, ...
/// On other frames the writer sets an empty "files" output and writes nothing.
inline bool writesThisFrame(CookContext& ctx)
{
    if (scheduledFrame(ctx.startFrame(), ctx.params().getInt("every"), ctx.frame())) return true;
    ctx.setOutput("files", std::make_shared<TextData>(""));
    return false;
}

/// An OutputPath parameter that names a frame-numbered sequence, resolved under --out as a
/// writer resolves its file (its folder made), with the #### of its file name kept: what a
/// node that reads or copies every frame's file (EncodeVideo, Retime) walks.
std::filesystem::path framePatternUnderOut(const CookContext& ctx, const std::string& param);

/// Adds firstFrame and skipEmpty to a writer of file sequences (WriteVDB, WritePoints), so
/// that its files are a numbered sequence from the first frame with something in it.
void addSequenceParams(NodeDecl& decl);

/// writesThisFrame for a writer with addSequenceParams: frames firstFrame, firstFrame + every,
/// ..., except empty ones (`empty`: this frame's value has nothing in it) under skipEmpty. It
/// reads this frame and the parameters only, never earlier frames, so a frame's file does not
/// depend on which frames a run cooks.
bool writesSequenceFrame(CookContext& ctx, bool empty);

}  // namespace cg
