#include "core/Node.h"

#include <cstdio>

#include "core/Error.h"
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
    if (it == mPrevious->end()) throw std::logic_error("previous frame lacks output '" + port + "'");
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
    if (!decl) throw std::logic_error("node type '" + mDecl.type + "' has no output '" + port + "'");
    if (!value || value->typeName() != decl->type)
        throw std::logic_error("output '" + port + "' must be a " + decl->type);
    mOutputs[port] = std::move(value);
}

std::filesystem::path CookContext::outputPath(const std::string& param) const
{
    std::filesystem::path p = util::framePath(mParams.getString(param), mEval.frame);
    if (p.is_relative()) p = mOutDir / p;
    std::filesystem::create_directories(p.parent_path());
    return p;
}

}  // namespace cg
