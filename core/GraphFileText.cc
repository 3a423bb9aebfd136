#include "core/GraphFileText.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace cg {

namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

/// Where a key goes in a graph written from scratch: the header before the nodes, a node's
/// type first; other keys after these, by name.
std::size_t keyRank(std::string_view key)
{
    constexpr std::array<std::string_view, 12> kOrder = {
        "cloudgraph", "description", "frames", "start",  "end",     "timeStep",
        "seed",       "type",        "inputs", "params", "comment", "nodes"};
    const auto it = std::find(kOrder.begin(), kOrder.end(), key);
    return static_cast<std::size_t>(it - kOrder.begin());
}

OrderedJson inWritingOrder(const Json& value)
{
    if (value.is_array()) {
        OrderedJson out = OrderedJson::array();
        for (const Json& item : value) out.push_back(inWritingOrder(item));
        return out;
    }
    switch (value.type()) {
        case Json::value_t::object:
            break;
        case Json::value_t::boolean:
            return value.get<bool>();
        case Json::value_t::number_integer:
            return value.get<std::int64_t>();
        case Json::value_t::number_unsigned:
            return value.get<std::uint64_t>();
        case Json::value_t::number_float:
            return value.get<double>();
        case Json::value_t::string:
            return value.get<std::string>();
        default:
            return nullptr;  // null: graph files hold no binary values
    }
    std::vector<std::string> keys;
    for (const auto& item : value.items()) keys.push_back(item.key());
    std::stable_sort(keys.begin(), keys.end(), [](const std::string& a, const std::string& b) {
        return keyRank(a) < keyRank(b);
    });
    OrderedJson out = OrderedJson::object();
    for (const std::string& key : keys) out[key] = inWritingOrder(value.at(key));
    return out;
}

/// `now`, with the keys `was` has in was's order and the values it did not change as
/// `was` wrote them.
OrderedJson keepLayout(const OrderedJson& was, const OrderedJson& now)
{
    if (!was.is_object() || !now.is_object()) return was == now ? was : now;
    OrderedJson out = OrderedJson::object();
    for (const auto& item : was.items())
        if (now.contains(item.key())) out[item.key()] = keepLayout(item.value(), now[item.key()]);
    for (const auto& item : now.items())
        if (!was.contains(item.key())) out[item.key()] = item.value();
    return out;
}

/// graphToJson leaves out what equals its default; the file may have said it anyway.
void keepStatedDefaults(const Graph& graph, const OrderedJson& was, Json& now)
{
    const Graph unset;
    if (!was.contains("seed") && graph.seed == unset.seed) now.erase("seed");
    if (!was.contains("timeStep") && graph.timeStep == unset.timeStep) now.erase("timeStep");
    const auto wasNodes = was.find("nodes");
    if (wasNodes == was.end() || !wasNodes->is_object()) return;
    for (const GraphNode& node : graph.nodes()) {
        const auto wasNode = wasNodes->find(node.id);
        if (wasNode == wasNodes->end() || !wasNode->is_object()) continue;
        const auto wasParams = wasNode->find("params");
        if (wasParams == wasNode->end() || !wasParams->is_object()) continue;
        Json& params = now["nodes"][node.id]["params"];
        for (const auto& item : wasParams->items())
            if (node.params.indexOf(item.key()) && !params.contains(item.key()))
                params[item.key()] = paramToJson(node.params.value(item.key()));
    }
}

bool isFlatArray(const OrderedJson& value)
{
    return value.is_array() && std::none_of(value.begin(), value.end(),
                                            [](const auto& v) { return v.is_structured(); });
}

void write(std::string& out, const OrderedJson& value, int depth)
{
    const std::string inner(2 * static_cast<std::size_t>(depth + 1), ' ');
    if (isFlatArray(value)) {
        out += '[';
        for (std::size_t i = 0; i < value.size(); ++i) out += (i ? ", " : "") + value[i].dump();
        out += ']';
    } else if (value.is_structured() && !value.empty()) {
        out += value.is_object() ? "{\n" : "[\n";
        bool first = true;
        for (const auto& item : value.items()) {
            out += (first ? "" : ",\n") + inner;
            first = false;
            if (value.is_object()) out += OrderedJson(item.key()).dump() + ": ";
            write(out, item.value(), depth + 1);
        }
        out += '\n' + inner.substr(2) + (value.is_object() ? '}' : ']');
    } else {
        out += value.dump();
    }
}

}  // namespace

std::string graphFileText(const Graph& graph, const std::string& layout)
{
    OrderedJson was = OrderedJson::parse(layout, nullptr, /*allow_exceptions=*/false);
    if (was.is_discarded() || !was.is_object()) was = OrderedJson::object();
    Json now = graphToJson(graph);
    keepStatedDefaults(graph, was, now);
    std::string text;
    write(text, keepLayout(was, inWritingOrder(now)), 0);
    return text + '\n';
}

}  // namespace cg
