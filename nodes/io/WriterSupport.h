#pragma once
/// What every writer node shares.

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/NodeDecl.h"

namespace cg {

/// True on the frames a writer declared with writerDecl writes: start, start + every, ...
/// On other frames the writer sets an empty "files" output and writes nothing.
inline bool writesThisFrame(CookContext& ctx)
{
    const auto every = ctx.params().getInt("every");
    if ((ctx.frame() - ctx.startFrame()) % every == 0) return true;
    ctx.setOutput("files", std::make_shared<TextData>(""));
    return false;
}

/// Adds firstFrame and skipEmpty to a writer of file sequences (WriteVDB, WritePoints), so
/// that its files are a numbered sequence from the first frame with something in it.
void addSequenceParams(NodeDecl& decl);

/// writesThisFrame for a writer with addSequenceParams: frames firstFrame, firstFrame + every,
/// ..., except empty ones (`empty`: this frame's value has nothing in it) under skipEmpty. It
/// reads this frame and the parameters only, never earlier frames, so a frame's file does not
/// depend on which frames a run cooks.
bool writesSequenceFrame(CookContext& ctx, bool empty);

}  // namespace cg
