// Fuzz target: serve's request-head parser (cli/http/HttpMessage.h) on any bytes, whole and
// cut at every length the server could have received. It must end in Incomplete, Complete or
// Refused within the limits; any exception, a sanitizer report or a broken invariant is a
// finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "cli/http/HttpMessage.h"

namespace {

void check(bool ok, const char* what)
{
    if (!ok) {
        std::fprintf(stderr, "invariant broken: %s\n", what);
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace cg::cli::http;
    Limits limits;
    limits.maxHeadBytes = 512;  // small, so that the fuzzer reaches the limits
    limits.maxHeaders = 8;
    limits.maxBodyBytes = 64;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    // As the server reads: a prefix, then the rest (a refusal or completion is final).
    for (const std::size_t cut : {size / 3, size}) {
        Request req;
        const HeadParse p = parseRequestHead(bytes.substr(0, cut), limits, req);
        if (p.state == HeadParse::State::Refused) {
            check(p.status >= 400 && p.status < 600 && !p.reason.empty(), "a refusal's status");
            break;
        }
        if (p.state != HeadParse::State::Complete) continue;
        check(p.headBytes <= cut && p.headBytes <= limits.maxHeadBytes, "head within the limit");
        check(req.headers.size() <= limits.maxHeaders, "headers within the limit");
        check(req.contentLength <= limits.maxBodyBytes, "body within the limit");
        check(!req.path.empty() && req.path.front() == '/', "the path is a path");
        check(req.path.find('\0') == std::string::npos, "no NUL in the path");
        std::string back;
        check(percentDecode(percentEncode(req.path), false, back) && back == req.path,
              "percent encoding round-trips");
        serializeResponse(Response{p.status == 0 ? 200 : p.status, "text/plain", req.path, {}});
        break;
    }
    return 0;
}
