#pragma once
/// The node interface. A node is a thin adapter: read parameters and inputs from the
/// CookContext, call an algorithm, set outputs.

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <typeinfo>

#include "core/Data.h"
#include "core/EvalContext.h"
#include "core/NodeDecl.h"
#include "core/Param.h"

namespace cg {

class CookContext;

class Node {
public:
    virtual ~Node() = default;
    /// Computes every output port for ctx.frame(). Must not keep state between calls:
    /// simulations read their previous frame through ctx.previous().
    virtual void cook(CookContext& ctx) = 0;
};

/// Output values of one cook, by port name.
using OutputMap = std::map<std::string, DataPtr>;

class CookContext {
public:
    CookContext(const NodeDecl& decl, const std::string& nodeId, const ParamSet& params,
                const EvalContext& eval, const std::filesystem::path& outDir);

    const std::string& nodeId() const { return mNodeId; }
    const NodeDecl& decl() const { return mDecl; }
    const ParamSet& params() const { return mParams; }
    int frame() const { return mEval.frame; }
    int startFrame() const { return mEval.startFrame; }
    /// The graph's last frame; a node that reads it declares readsFrameRange.
    int endFrame() const { return mEval.endFrame; }
    double timeStep() const { return mEval.timeStep; }
    std::uint64_t seed() const { return mEval.seed; }
    void checkCancelled() const { mEval.cancel->throwIfCancelled(); }
    const CancelToken& cancelToken() const { return *mEval.cancel; }

    /// The value on an input port; nullptr only for an unconnected optional input.
    template <class T>
    std::shared_ptr<const T> input(const std::string& port) const
    {
        return cast<T>(rawInput(port), port);
    }
    /// Simulations: this node's own output at frame-1; nullptr on the start frame.
    template <class T>
    std::shared_ptr<const T> previous(const std::string& port) const
    {
        return cast<T>(rawPrevious(port), port);
    }
    bool isStartFrame() const { return mPrevious == nullptr; }

    void setOutput(const std::string& port, DataPtr value);

    /// Resolves an OutputPath parameter under the run's output directory, with a ####
    /// pattern replaced by the zero-padded frame. The parent directory is created. Unless
    /// the graph allows paths outside the output directory, each directory of the path is
    /// resolved beneath it: InputError (naming the parameter) when one leads out of it
    /// through a symbolic link, is not a directory, or a directory sits where the file goes.
    std::filesystem::path outputPath(const std::string& param) const;

    // Engine side.
    void setInput(const std::string& port, DataPtr value) { mInputs[port] = std::move(value); }
    void setPrevious(const OutputMap* previous) { mPrevious = previous; }
    OutputMap takeOutputs() { return std::move(mOutputs); }

private:
    DataPtr rawInput(const std::string& port) const;
    DataPtr rawPrevious(const std::string& port) const;
    template <class T>
    std::shared_ptr<const T> cast(const DataPtr& p, const std::string& port) const
    {
        if (!p) return nullptr;
        auto typed = std::dynamic_pointer_cast<const T>(p);
        if (!typed) badType(port, typeid(T).name(), p->typeName());
        return typed;
    }
    [[noreturn]] void badType(const std::string& port, const char* want,
                              const std::string& got) const;

    const NodeDecl& mDecl;
    std::string mNodeId;
    const ParamSet& mParams;
    const EvalContext& mEval;
    std::filesystem::path mOutDir;
    std::map<std::string, DataPtr> mInputs;
    const OutputMap* mPrevious = nullptr;
    OutputMap mOutputs;
};

}  // namespace cg
