#include "cli/ApiBody.h"

#include <cstdint>

#include "core/Error.h"
#include "core/JsonParse.h"

namespace cg::cli {

using http::Request;
using http::Response;

Response jsonReply(int status, const nlohmann::json& body)
{
    Response res;
    res.status = status;
    // Messages may quote the bytes a client sent, which need not be UTF-8.
    res.body = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return res;
}

Response errorReply(int status, const std::string& message)
{
    return jsonReply(status, {{"error", message}});
}

nlohmann::json jsonBody(const Request& req, int maxDepth)
{
    nlohmann::json body;
    try {
        body = parseJsonStrict(req.body, "request body", maxDepth);
    } catch (const InputError& e) {
        throw Refused{errorReply(400, e.what())};
    }
    if (!body.is_object()) throw Refused{errorReply(400, "the request body must be a JSON object")};
    return body;
}

std::string stringField(const nlohmann::json& body, const char* key)
{
    const auto it = body.find(key);
    if (it == body.end() || !it->is_string())
        throw Refused{errorReply(400, std::string("'") + key + "' must be a string")};
    return it->get<std::string>();
}

long integerField(const nlohmann::json& body, const char* key)
{
    const auto it = body.find(key);
    if (it == body.end() || !it->is_number_integer() || it->get<std::int64_t>() < -(1L << 40) ||
        it->get<std::int64_t>() > (1L << 40))
        throw Refused{errorReply(400, std::string("'") + key + "' must be an integer")};
    return static_cast<long>(it->get<std::int64_t>());
}

int frameField(const nlohmann::json& body, const FrameRange& frames)
{
    const auto it = body.find("frame");
    if (it == body.end() || !it->is_number_integer())
        throw Refused{errorReply(400, "'frame' must be an integer")};
    // nlohmann keeps integers above INT64_MAX unsigned: no frame is that large.
    const bool fits = !it->is_number_unsigned() || it->get<std::uint64_t>() <= INT64_MAX;
    const std::int64_t f = fits ? it->get<std::int64_t>() : 0;
    if (!fits || f < frames.start || f > frames.end)
        throw Refused{errorReply(400, "frame " + it->dump() + " is outside the graph's frames " +
                                          std::to_string(frames.start) + ":" +
                                          std::to_string(frames.end))};
    return static_cast<int>(f);
}

bool boolField(const nlohmann::json& body, const char* key, bool fallback)
{
    const auto it = body.find(key);
    if (it == body.end()) return fallback;
    if (!it->is_boolean())
        throw Refused{errorReply(400, std::string("'") + key + "' must be true or false")};
    return it->get<bool>();
}

}  // namespace cg::cli
