#include "core/RunReport.h"

#include <algorithm>
#include <map>

namespace cg {

const char* cookStatusName(CookStatus s)
{
    switch (s) {
        case CookStatus::Cooked:
            return "cooked";
        case CookStatus::MemoryHit:
            return "memory-hit";
        case CookStatus::DiskHit:
            return "disk-hit";
        case CookStatus::Verified:
            return "verified";
        case CookStatus::Idle:
            return "idle";
    }
    return "?";
}

void RunReport::add(CookRecord record)
{
    std::lock_guard<std::mutex> lock(mMutex);
    mRecords.push_back(std::move(record));
}

void RunReport::clear()
{
    std::lock_guard<std::mutex> lock(mMutex);
    mRecords.clear();
}

std::vector<CookRecord> RunReport::records() const
{
    std::vector<CookRecord> out;
    {
        std::lock_guard<std::mutex> lock(mMutex);
        out = mRecords;
    }
    std::stable_sort(out.begin(), out.end(), [](const CookRecord& a, const CookRecord& b) {
        return a.frame != b.frame ? a.frame < b.frame : a.order < b.order;
    });
    return out;
}

std::size_t RunReport::cookCount(const std::string& node) const
{
    std::lock_guard<std::mutex> lock(mMutex);
    return static_cast<std::size_t>(std::count_if(
        mRecords.begin(), mRecords.end(),
        [&](const CookRecord& r) { return r.node == node && r.status == CookStatus::Cooked; }));
}

nlohmann::json RunReport::toJson() const
{
    nlohmann::json entries = nlohmann::json::array();
    std::map<std::string, nlohmann::json> perNode;
    std::size_t cooked = 0, memoryHits = 0, diskHits = 0, verified = 0, idle = 0, bytes = 0;
    double seconds = 0.0;
    for (const CookRecord& r : records()) {
        nlohmann::json e = {{"node", r.node},       {"type", r.type},
                            {"frame", r.frame},     {"status", cookStatusName(r.status)},
                            {"seconds", r.seconds}, {"key", r.key.hex()},
                            {"bytes", r.bytes}};
        if (r.status == CookStatus::Cooked) e["reason"] = r.reason;
        if (!r.values.empty()) e["values"] = r.values;
        entries.push_back(std::move(e));

        nlohmann::json& n = perNode[r.node];
        if (n.is_null()) n = {{"cooked", 0}, {"hits", 0}, {"seconds", 0.0}};
        if (r.status == CookStatus::Cooked) {
            n["cooked"] = n["cooked"].get<int>() + 1;
            ++cooked;
        } else {
            n["hits"] = n["hits"].get<int>() + 1;
            ++(r.status == CookStatus::MemoryHit ? memoryHits
               : r.status == CookStatus::DiskHit ? diskHits
               : r.status == CookStatus::Idle    ? idle
                                                 : verified);
        }
        n["seconds"] = n["seconds"].get<double>() + r.seconds;
        seconds += r.seconds;
        bytes += r.bytes;
    }
    return {{"records", entries},
            {"nodes", perNode},
            {"totals",
             {{"cooked", cooked},
              {"memoryHits", memoryHits},
              {"diskHits", diskHits},
              {"verified", verified},
              {"idle", idle},
              {"nodeSeconds", seconds},
              {"bytes", bytes}}}};
}

}  // namespace cg
