#include "core/CookHistory.h"

#include <vector>

#include "core/DiskCache.h"

namespace cg {

namespace {

std::string join(const std::vector<std::string>& parts)
{
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
    return out;
}

/// What differs between two identities, in words; empty when nothing does.
std::vector<std::string> identityChanges(const nlohmann::json& was, const nlohmann::json& now)
{
    if (was.value("type", "") != now["type"] || was.value("version", -1) != now["version"])
        return {"node type or version changed"};
    std::vector<std::string> why;
    const nlohmann::json wasParams = was.value("params", nlohmann::json::object());
    for (const auto& [name, value] : now["params"].items()) {
        auto w = wasParams.find(name);
        if (w == wasParams.end()) {
            why.push_back("parameter '" + name + "' is new");
        } else if (*w != value) {
            why.push_back("parameter '" + name + "' changed (" + w->get<std::string>() + " -> " +
                          value.get<std::string>() + ")");
        }
    }
    const nlohmann::json wasContext = was.value("context", nlohmann::json::object());
    for (const auto& [name, value] : now["context"].items())
        if (wasContext.value(name, nlohmann::json()) != value) why.push_back(name + " changed");
    return why;
}

}  // namespace

const nlohmann::json* CookHistory::committed(const std::string& name)
{
    auto it = mCommitted.find(name);
    if (it == mCommitted.end()) {
        std::optional<nlohmann::json> stored;
        if (mDisk) stored = mDisk->loadRecord(name);
        if (stored && !stored->is_object()) stored.reset();
        it = mCommitted.emplace(name, std::move(stored)).first;
    }
    return it->second ? &*it->second : nullptr;
}

std::string CookHistory::explain(const std::string& name, const nlohmann::json& identity,
                                 const std::string& frameKey, const nlohmann::json& inputs,
                                 bool simulation)
{
    std::lock_guard<std::mutex> lock(mMutex);
    nlohmann::json& pending = mPending[name];
    if (pending.is_null()) {
        pending = identity;
        pending["frames"] = nlohmann::json::object();
    }
    pending["frames"][frameKey] = inputs;

    const nlohmann::json* was = committed(name);
    if (!was) return "first cook";
    const std::vector<std::string> changes = identityChanges(*was, identity);
    if (!changes.empty()) return join(changes);

    const nlohmann::json frames = was->value("frames", nlohmann::json::object());
    auto f = frames.find(frameKey);
    if (f == frames.end()) return simulation ? "simulation step to frame " + frameKey : "new frame";
    std::vector<std::string> why;
    for (const auto& [port, key] : inputs.items()) {
        auto w = f->find(port);
        if (w == f->end() || *w != key) why.push_back("input '" + port + "' changed");
    }
    if (!why.empty()) return join(why);
    return "not in cache (evicted, damaged or never stored)";
}

void CookHistory::commit()
{
    std::lock_guard<std::mutex> lock(mMutex);
    for (auto& [name, record] : mPending) {
        const nlohmann::json* was = committed(name);
        nlohmann::json merged = record;
        if (was && identityChanges(*was, record).empty()) {
            // Same node settings: keep the frames this batch did not touch.
            merged["frames"] = was->value("frames", nlohmann::json::object());
            merged["frames"].update(record["frames"]);
        }
        if (mDisk) mDisk->storeRecord(name, merged);
        mCommitted[name] = std::move(merged);
    }
    mPending.clear();
}

}  // namespace cg
