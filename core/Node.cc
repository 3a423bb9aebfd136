#include "core/Node.h"

#include <cstdio>

#include "core/Error.h"
#include "util/Beneath.h"
#include "util/FramePattern.h"

namespace cg {

CookContext::CookContext(const NodeDecl& decl, const std::string& nodeId, const ParamSet& params,
                         const EvalContext& eval, const std::filesystem::path& outDir)
    : mDecl(decl), mNodeId(nodeId), mParams(params), mEval(eval), mOutDir(outDir)
{
}

DataPtr CookContext::rawInput(const std::string& port) const
{
    const PortDecl* decl = mDecl.findInput(port);
    if (!decl) throw std::logic_error("node type '" + mDecl.type + "' has no input '" + port + "'");
    auto it = mInputs.find(port);
    if (it == mInputs.end() || !it->second) {
        if (decl->optional) return nullptr;
        throw std::logic_error("required input '" + port + "' was not provided");
    }
    return it->second;
}

DataPtr CookContext::rawPrevious(const std::string& port) const
{
    if (!mDecl.simulation)
        throw std::logic_error("node type '" + mDecl.type + "' is not a simulation");
    if (!mPrevious) return nullptr;
    auto it = mPrevious->find(port);
    if (it == mPrevious->end())
        throw std::logic_error("previous frame lacks output '" + port + "'");
    return it->second;
}

void CookContext::badType(const std::string& port, const char* want, const std::string& got) const
{
    throw std::logic_error("port '" + port + "' holds a " + got + ", not the " + want +
                           " the node expects");
}

void CookContext::setOutput(const std::string& port, DataPtr value)
{
    const PortDecl* decl = mDecl.findOutput(port);
    if (!decl)
        throw std::logic_error("node type '" + mDecl.type + "' has no output '" + port + "'");
    if (!value || value->typeName() != decl->type)
        throw std::logic_error("output '" + port + "' must be a " + decl->type);
    mOutputs[port] = std::move(value);
}

std::filesystem::path CookContext::outputPath(const std::string& param) const
{
    const std::filesystem::path file = util::framePath(mParams.getString(param), mEval.frame);
    if (mEval.allowOutsideOut) {
        const std::filesystem::path p = file.is_relative() ? mOutDir / file : file;
        std::filesystem::create_directories(p.parent_path());
        return p;
    }
    // Loading refused absolute paths and "..": only a symbolic link inside the output
    // directory could lead out of it now.
    if (const std::string problem = util::makeOutputPlace(mOutDir, file); !problem.empty()) {
        const bool leaves = problem.find("leads outside") != std::string::npos;
        throw InputError(mNodeId + "/params/" + param,
                         "cannot write '" + (mOutDir / file).string() + "': " + problem +
                             (leaves ? " (use --allow-outside-out to permit)" : ""));
    }
    return mOutDir / file;
}

}  // namespace cg
