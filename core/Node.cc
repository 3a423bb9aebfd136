#include "core/Node.h"

#include <cstdio>

#include "core/Error.h"

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
    std::string name = mParams.getString(param);
    // Replace the first run of '#' by the zero-padded frame: name.####.ply -> name.0042.ply
    const auto first = name.find('#');
    if (first != std::string::npos) {
        auto last = name.find_first_not_of('#', first);
        if (last == std::string::npos) last = name.size();
        const int width = static_cast<int>(last - first);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%0*d", width, mEval.frame);
        name.replace(first, last - first, buf);
    }
    std::filesystem::path p(name);
    if (p.is_relative()) p = mOutDir / p;
    std::filesystem::create_directories(p.parent_path());
    return p;
}

}  // namespace cg
