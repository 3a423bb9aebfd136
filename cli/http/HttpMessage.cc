#include "cli/http/HttpMessage.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>

namespace cg::cli::http {

namespace {

bool isTokenChar(char c)
{
    // RFC 9110's tchar.
    static constexpr std::string_view kSymbols = "!#$%&'*+-.^_`|~";
    return std::isalnum(static_cast<unsigned char>(c)) || kSymbols.find(c) != kSymbols.npos;
}

bool isToken(std::string_view s)
{
    return !s.empty() && std::all_of(s.begin(), s.end(), isTokenChar);
}

/// A field value may hold visible characters, spaces, tabs and obs-text, never controls.
bool isFieldValue(std::string_view s)
{
    return std::none_of(s.begin(), s.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return (u < 0x20 && c != '\t') || u == 0x7f;
    });
}

std::string_view trimWhitespace(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

std::string lowerCase(std::string_view s)
{
    std::string lower(s);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower;
}

HeadParse refuse(int status, std::string reason)
{
    HeadParse p;
    p.state = HeadParse::State::Refused;
    p.status = status;
    p.reason = std::move(reason);
    return p;
}

/// Splits the head into its lines (without their CRLF or LF); the last is the empty one.
std::vector<std::string_view> headLines(std::string_view head)
{
    std::vector<std::string_view> lines;
    while (!head.empty()) {
        const std::size_t end = head.find('\n');
        std::string_view line = head.substr(0, end);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        lines.push_back(line);
        head.remove_prefix(end + 1);
    }
    return lines;
}

/// The end of the head (one past its blank line) in `received`, or npos.
std::size_t headEnd(std::string_view received)
{
    for (std::size_t at = received.find('\n'); at != received.npos;
         at = received.find('\n', at + 1)) {
        const std::size_t next = at + 1;
        if (received.substr(next, 1) == "\n") return next + 1;
        if (received.substr(next, 2) == "\r\n") return next + 2;
    }
    return received.npos;
}

/// "METHOD SP target SP HTTP/1.x" into request; "" or why it is refused (with its status).
HeadParse parseRequestLine(std::string_view line, Request& request)
{
    const std::size_t sp1 = line.find(' ');
    const std::size_t sp2 = sp1 == line.npos ? line.npos : line.find(' ', sp1 + 1);
    if (sp2 == line.npos || line.find(' ', sp2 + 1) != line.npos)
        return refuse(400, "malformed request line");
    const std::string_view method = line.substr(0, sp1);
    const std::string_view target = line.substr(sp1 + 1, sp2 - sp1 - 1);
    const std::string_view version = line.substr(sp2 + 1);
    if (!isToken(method)) return refuse(400, "malformed method");
    if (version != "HTTP/1.1" && version != "HTTP/1.0")
        return refuse(505, "only HTTP/1.0 and HTTP/1.1 are served");
    if (target.empty() || target.front() != '/' || !isFieldValue(target) ||
        target.find_first_of(" \t") != target.npos)
        return refuse(400, "the request target must be a path");
    request.method = std::string(method);
    request.target = std::string(target);
    const std::size_t q = target.find('?');
    if (!percentDecode(target.substr(0, q), false, request.path))
        return refuse(400, "bad percent escape in the path");
    if (q == target.npos) return {};
    std::string_view query = target.substr(q + 1);
    while (!query.empty()) {
        const std::size_t amp = query.find('&');
        const std::string_view pair = query.substr(0, amp);
        query = amp == query.npos ? std::string_view() : query.substr(amp + 1);
        const std::size_t eq = pair.find('=');
        std::string name;
        std::string value;
        if (!percentDecode(pair.substr(0, eq), true, name) ||
            (eq != pair.npos && !percentDecode(pair.substr(eq + 1), true, value)))
            return refuse(400, "bad percent escape in the query");
        if (!name.empty()) request.query.emplace(std::move(name), std::move(value));
    }
    return {};
}

/// Reads Content-Length (one whole number, repeated only with the same value).
HeadParse parseFraming(const Limits& limits, Request& request)
{
    if (request.header("transfer-encoding"))
        return refuse(501, "Transfer-Encoding is not supported; send a Content-Length");
    const std::string* first = request.header("content-length");
    if (!first) return {};
    for (const auto& [name, value] : request.headers)
        if (name == "content-length" && value != *first)
            return refuse(400, "conflicting Content-Length headers");
    std::size_t length = 0;
    const char* end = first->data() + first->size();
    const auto [ptr, ec] = std::from_chars(first->data(), end, length);
    if (first->empty()) return refuse(400, "malformed Content-Length");
    if (ec == std::errc::result_out_of_range)
        return refuse(413,
                      "the body is larger than " + std::to_string(limits.maxBodyBytes) + " bytes");
    if (ec != std::errc() || ptr != end) return refuse(400, "malformed Content-Length");
    if (length > limits.maxBodyBytes)
        return refuse(413,
                      "the body is larger than " + std::to_string(limits.maxBodyBytes) + " bytes");
    request.contentLength = length;
    return {};
}

}  // namespace

const std::string* Request::header(std::string_view lowerName) const
{
    for (const auto& [name, value] : headers)
        if (name == lowerName) return &value;
    return nullptr;
}

std::string Request::headerOr(std::string_view lowerName, std::string fallback) const
{
    if (const std::string* value = header(lowerName)) return *value;
    return fallback;
}

bool percentDecode(std::string_view text, bool plusIsSpace, std::string& decoded)
{
    decoded.clear();
    decoded.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '+' && plusIsSpace) {
            decoded.push_back(' ');
        } else if (c != '%') {
            decoded.push_back(c);
        } else {
            unsigned value = 0;
            if (i + 2 >= text.size()) return false;
            const auto [ptr, ec] =
                std::from_chars(text.data() + i + 1, text.data() + i + 3, value, 16);
            if (ec != std::errc() || ptr != text.data() + i + 3 || value == 0) return false;
            decoded.push_back(static_cast<char>(value));
            i += 2;
        }
    }
    return true;
}

std::string percentEncode(std::string_view text)
{
    std::string encoded;
    for (const char c : text) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_' ||
            c == '~') {
            encoded.push_back(c);
        } else {
            char escape[4];
            std::snprintf(escape, sizeof escape, "%%%02X", static_cast<unsigned char>(c));
            encoded += escape;
        }
    }
    return encoded;
}

HeadParse parseRequestHead(std::string_view received, const Limits& limits, Request& request)
{
    const std::size_t end = headEnd(received.substr(0, limits.maxHeadBytes + 1));
    if (end == received.npos || end > limits.maxHeadBytes) {
        if (received.size() > limits.maxHeadBytes)
            return refuse(431, "the request head is larger than " +
                                   std::to_string(limits.maxHeadBytes) + " bytes");
        // Refuse early what can never become a request line, so that junk is not buffered.
        if (!received.empty() && received.find('\n') == received.npos &&
            !isTokenChar(received.front()))
            return refuse(400, "malformed request line");
        return {};
    }
    request = Request();
    std::vector<std::string_view> lines = headLines(received.substr(0, end));
    lines.pop_back();  // the blank line
    if (lines.empty()) return refuse(400, "malformed request line");
    if (lines.size() - 1 > limits.maxHeaders)
        return refuse(431, "more than " + std::to_string(limits.maxHeaders) + " header lines");
    if (HeadParse p = parseRequestLine(lines.front(), request);
        p.state == HeadParse::State::Refused)
        return p;
    for (std::size_t i = 1; i < lines.size(); ++i) {
        const std::string_view line = lines[i];
        const std::size_t colon = line.find(':');
        if (colon == line.npos || !isToken(line.substr(0, colon)))
            return refuse(400, "malformed header line");
        const std::string_view value = trimWhitespace(line.substr(colon + 1));
        if (!isFieldValue(value)) return refuse(400, "control characters in a header");
        request.headers.emplace_back(lowerCase(line.substr(0, colon)), std::string(value));
    }
    if (HeadParse p = parseFraming(limits, request); p.state == HeadParse::State::Refused) return p;
    HeadParse done;
    done.state = HeadParse::State::Complete;
    done.headBytes = end;
    return done;
}

const char* reasonPhrase(int status)
{
    switch (status) {
        case 200:
            return "OK";
        case 400:
            return "Bad Request";
        case 403:
            return "Forbidden";
        case 404:
            return "Not Found";
        case 405:
            return "Method Not Allowed";
        case 408:
            return "Request Timeout";
        case 409:
            return "Conflict";
        case 413:
            return "Content Too Large";
        case 431:
            return "Request Header Fields Too Large";
        case 500:
            return "Internal Server Error";
        case 501:
            return "Not Implemented";
        case 503:
            return "Service Unavailable";
        case 505:
            return "HTTP Version Not Supported";
        default:
            return "Status";
    }
}

std::string serializeResponse(const Response& response)
{
    std::string out = "HTTP/1.1 " + std::to_string(response.status) + " " +
                      reasonPhrase(response.status) + "\r\n";
    out += "Content-Type: " + response.contentType + "\r\n";
    out += "Content-Length: " + std::to_string(response.body.size()) + "\r\n";
    out += "Connection: close\r\n";
    out += "X-Content-Type-Options: nosniff\r\n";
    for (const auto& [name, value] : response.headers) out += name + ": " + value + "\r\n";
    out += "\r\n";
    out += response.body;
    return out;
}

}  // namespace cg::cli::http
