#pragma once
/// What happened in a run: for each node and frame, cooked or cache hit, why it cooked,
/// wall time, output key and bytes; plus totals. Written by `cloudgraph run --report FILE`.

#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/Hash.h"

namespace cg {

/// Verified: a writer whose files from an earlier run still hold its recorded bytes
/// (WrittenFiles); it neither cooks nor writes.
/// Idle: a writer off its schedule on this frame (NodeDecl::idleOnFrame), not cooked.
enum class CookStatus { Cooked, MemoryHit, DiskHit, Verified, Idle };

const char* cookStatusName(CookStatus s);

struct CookRecord {
    std::string node;
    std::string type;
    int frame = 0;
    std::size_t order = 0;  ///< topological index, to list records in a stable order
    CookStatus status = CookStatus::Cooked;
    std::string reason;    ///< why it cooked; empty for hits
    double seconds = 0.0;  ///< wall time of the cook or the lookup
    Key key;
    std::size_t bytes = 0;
    /// Small values among the outputs (numbers, short text), so a report shows e.g. counts.
    nlohmann::json values = nlohmann::json::object();
};

/// Thread-safe collector of CookRecords.
class RunReport {
public:
    void add(CookRecord record);
    void clear();
    /// Records sorted by frame, then topological order.
    std::vector<CookRecord> records() const;
    /// How many times `node` was cooked (not counting cache hits).
    std::size_t cookCount(const std::string& node) const;
    nlohmann::json toJson() const;

private:
    mutable std::mutex mMutex;
    std::vector<CookRecord> mRecords;
};

}  // namespace cg
