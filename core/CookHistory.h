#pragma once
/// Remembers what each node read the last time it cooked, so a run report can say why a
/// node cooked again: first cook, which parameter or input changed, a new frame, or a value
/// that was evicted or damaged. Records live in memory and, with a disk cache, beside it.
///
/// Explanations compare with the state before the current batch of cooks (one cookFrames
/// call); commit() then makes the batch the new reference.

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace cg {

class DiskCache;

class CookHistory {
public:
    explicit CookHistory(std::shared_ptr<DiskCache> disk) : mDisk(std::move(disk)) {}

    /// `identity` holds what is the same for every frame (type, version, params, context);
    /// `inputs` the input keys at this frame; `frameKey` names the frame ("all" for a node
    /// whose output ignores the frame). Thread-safe.
    std::string explain(const std::string& name, const nlohmann::json& identity,
                        const std::string& frameKey, const nlohmann::json& inputs, bool simulation);
    /// Makes this batch's records the reference and stores them on disk.
    void commit();

private:
    const nlohmann::json* committed(const std::string& name);

    std::shared_ptr<DiskCache> mDisk;
    std::mutex mMutex;
    std::map<std::string, std::optional<nlohmann::json>> mCommitted;  ///< nullopt: none known
    std::map<std::string, nlohmann::json> mPending;
};

}  // namespace cg
