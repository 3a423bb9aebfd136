#pragma once
/// What every writer node shares.

#include "core/CoreData.h"
#include "core/Node.h"

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

}  // namespace cg
