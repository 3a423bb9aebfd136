#pragma once
/// A node type is declared once: ports, parameters, version, docs. JSON validation, the
/// node reference and the default content key are all derived from this declaration.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/Param.h"

namespace cg {

class Node;
class Hasher;

struct PortDecl {
    std::string name;
    std::string type;       ///< a registered data type name, e.g. "Float"
    std::string doc;        ///< one line
    bool optional = false;  ///< inputs only: may be left unconnected
};

/// What a node may do beyond reading its parameters and inputs.
struct ParamChecker;

struct NodeDecl {
    std::string type;      ///< unique type name, e.g. "NoiseMap"
    int version = 1;       ///< bump when the output for the same inputs changes
    std::string category;  ///< for the reference: "atmosphere", "util", ...
    std::string doc;       ///< a paragraph: what it computes, which equations
    std::vector<PortDecl> inputs;
    std::vector<PortDecl> outputs;
    std::vector<ParamDecl> params;

    /// The output changes with the frame even when the inputs do not.
    bool frameDependent = false;
    /// When set, whether it does depends on the parameters (the Renderer's camera moves only
    /// with keys): frameDependent is then ignored. See dependsOnFrame().
    std::function<bool(const ParamSet&)> frameDependentIf;
    /// Frame N is stepped from this node's own output at frame N-1 (see CookContext::previous).
    /// Implies frameDependent.
    bool simulation = false;
    /// The node writes files. It cooks on every run, unless a disk cache records that its
    /// files from an earlier run are still there unchanged (WrittenFiles).
    bool writesFiles = false;
    /// The node reads what other frames wrote (EncodeVideo reads every PNG). A chunked run
    /// (`run --chunk`) leaves it out; a farm's last job runs it once every chunk is written.
    bool gathersFrames = false;
    /// Whether the output goes to the disk cache. False for large outputs that are cheaper to
    /// cook again than to store and read back (e.g. a frame's cloud particles); the memory
    /// cache still keeps them.
    bool cacheOnDisk = true;
    /// Whether the memory cache keeps the output after its frame is evaluated. False for
    /// outputs so large and so cheap to cook that keeping frames of them costs more (page
    /// faults, evictions, gigabytes of resident memory) than cooking again when asked twice.
    bool cacheInMemory = true;
    /// The output at a frame depends on nothing but the inputs at that frame, the parameters
    /// and the frame itself, and a cook does nothing else: two frames of the node may cook at
    /// once (one frame's render beside the next one's, so that the cores one frame's serial
    /// parts leave idle are not lost). Never a simulation, a writer or a logger.
    bool framesInAnyOrder = false;
    /// The node reads the evaluation context's time step or seed (hashed into its key).
    bool readsTimeStep = false;
    bool readsSeed = false;
    /// The node reads the graph's first and last frame (hashed into its key).
    bool readsFrameRange = false;

    std::function<std::unique_ptr<Node>()> create;
    /// Extra checks across parameters (e.g. allocation sizes); throw through ParamChecker.
    std::function<void(const ParamSet&, const ParamChecker&)> validate;
    /// A writer's frames: how many of the frames start..end it writes a file on (a count above
    /// 1 means "several"; writers stop counting there). With it, an output file name without
    /// a #### frame number that would be written on several frames is refused at load, since
    /// each frame would overwrite the last. Unset: not checked (a writer that writes once).
    std::function<int(const ParamSet&, int start, int end)> framesWritten;
    /// A writer's idle frames: true where it writes nothing whatever its inputs (a frame off
    /// its `every` schedule). There the evaluator gives each of its outputs (all Text) as an
    /// empty file list without cooking it or what only it needs, so a VDB written every 100
    /// frames does not voxelize the 99 between. Unset: the writer cooks on every frame.
    std::function<bool(const ParamSet&, int frame, int start)> idleOnFrame;
    /// Extra key ingredients, e.g. the content hash of an input file.
    std::function<void(const ParamSet&, Hasher&)> hashExtra;
    /// JSON parameter values that make a quick cook, for tests (the contract test applies them
    /// with Graph::setParam before cooking). The key "__skipCook" (any value) marks a node the
    /// contract test cannot cook on its own (e.g. one that needs a file); its own tests cover it.
    std::map<std::string, std::string> quickParams;

    const PortDecl* findInput(const std::string& name) const;
    const PortDecl* findOutput(const std::string& name) const;
    const ParamDecl* findParam(const std::string& name) const;
};

/// Passed to NodeDecl::validate: names the failing parameter with its JSON pointer.
/// Whether a node of `decl` with `params` makes a different output on each frame, whatever its
/// inputs: its frameDependentIf, else frameDependent. (A simulation is stepped on every frame
/// too; callers test that apart.)
inline bool dependsOnFrame(const NodeDecl& decl, const ParamSet& params)
{
    return decl.frameDependentIf ? decl.frameDependentIf(params) : decl.frameDependent;
}

struct ParamChecker {
    std::string nodePointer;             ///< e.g. /nodes/noise
    std::uint64_t allocationLimitBytes;  ///< the most one node may allocate
    [[noreturn]] void fail(const std::string& param, const std::string& message) const;
    /// Throws unless count * bytesPerItem fits in the limit, with overflow-checked 64-bit
    /// arithmetic. `counts` are the user-given sizes (e.g. nx, ny); negative counts fail.
    void checkAllocation(const std::string& param, const std::vector<std::int64_t>& counts,
                         std::uint64_t bytesPerItem) const;
};

}  // namespace cg
