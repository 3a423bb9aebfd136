#pragma once
/// Reading the JSON bodies of serve's /api/* requests, and the JSON replies. A reader that
/// meets a body it refuses throws Refused with the 400 reply to send instead, so that a
/// route reads as the list of what it needs.

#include <string>

#include <nlohmann/json.hpp>

#include "cli/http/HttpMessage.h"
#include "core/Graph.h"

namespace cg::cli {

/// A reply of `status` with `body` as JSON (bytes that are not UTF-8 replaced).
http::Response jsonReply(int status, const nlohmann::json& body);
/// {"error": message}.
http::Response errorReply(int status, const std::string& message);

/// Thrown by the readers below with the reply to send instead.
struct Refused {
    http::Response response;
};

/// The request's body as a JSON object, read with the graph loader's strict, depth-limited
/// parser (a deeply nested body is refused, never recursed into).
nlohmann::json jsonBody(const http::Request& req, int maxDepth);
/// body[key] as a string.
std::string stringField(const nlohmann::json& body, const char* key);
/// body[key] as an integer within +-2^40 (a size, checked further by its reader).
long integerField(const nlohmann::json& body, const char* key);
/// body["frame"] as a frame of `frames`, checked before it is narrowed to an int.
int frameField(const nlohmann::json& body, const FrameRange& frames);
/// body[key] as a boolean, `fallback` when absent.
bool boolField(const nlohmann::json& body, const char* key, bool fallback);

}  // namespace cg::cli
