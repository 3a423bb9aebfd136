#pragma once
/// The HTTP/1.1 messages `cloudgraph serve` reads and writes, and the parser of a request's
/// head. The parser is a pure function over the bytes received so far, so that the server can
/// call it after every read and a fuzzer can call it on anything.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cg::cli::http {

/// What a request may be: anything larger is refused before it is read further.
struct Limits {
    std::size_t maxHeadBytes = 32 * 1024;  ///< request line and headers (431 past it)
    std::size_t maxHeaders = 100;          ///< header lines (431 past it)
    std::size_t maxBodyBytes = 1 << 20;    ///< Content-Length (413 past it)
};

struct Request {
    std::string method;  ///< as sent ("GET", "POST")
    std::string target;  ///< as sent, an origin-form target ("/api/preview?node=a")
    std::string path;    ///< the target before '?', percent-decoded
    std::map<std::string, std::string> query;  ///< decoded; a repeated name keeps its first
    std::vector<std::pair<std::string, std::string>> headers;  ///< names in lower case
    std::size_t contentLength = 0;
    std::string body;

    /// The first header called `lowerName`, or nullptr.
    const std::string* header(std::string_view lowerName) const;
    /// The first header called `lowerName`, or "".
    std::string headerOr(std::string_view lowerName, std::string fallback = "") const;
};

struct Response {
    int status = 200;
    std::string contentType = "application/json";
    std::string body;
    std::vector<std::pair<std::string, std::string>> headers;  ///< besides the framing ones
};

/// The bytes of `response` on the wire, framed with Content-Length and Connection: close.
std::string serializeResponse(const Response& response);

/// The reason phrase of a status code ("Not Found").
const char* reasonPhrase(int status);

/// Where parsing the bytes received so far stands.
struct HeadParse {
    enum class State { Incomplete, Complete, Refused };
    State state = State::Incomplete;
    std::size_t headBytes = 0;  ///< Complete: the head's length, its blank line included
    int status = 0;             ///< Refused: 400, 413, 431, 501 or 505
    std::string reason;         ///< Refused: why, for the reply
};

/// Parses the head of a request from the start of `received`, into `request` (its method,
/// target, path, query, headers and contentLength; not its body). Incomplete until the blank
/// line that ends the head has arrived, and Refused as soon as the bytes cannot begin a
/// request within `limits`: a head longer than maxHeadBytes or with more than maxHeaders
/// lines, a malformed request line or header, a target that is not a path, a bad percent
/// escape, a Content-Length that is not one whole number or exceeds maxBodyBytes, or a
/// Transfer-Encoding (bodies are framed by Content-Length only).
HeadParse parseRequestHead(std::string_view received, const Limits& limits, Request& request);

/// `text` with %XX escapes decoded (and '+' as a space when `plusIsSpace`); false when an
/// escape is malformed or decodes to a NUL.
bool percentDecode(std::string_view text, bool plusIsSpace, std::string& decoded);

/// `text` with every byte but RFC 3986's unreserved characters written as %XX.
std::string percentEncode(std::string_view text);

}  // namespace cg::cli::http
