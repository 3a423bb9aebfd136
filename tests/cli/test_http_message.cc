// serve's request parser: what a request head may be, and what is refused before it is read
// further (sizes, framing, malformed lines).

#include <gtest/gtest.h>

#include <string>

#include "cli/http/HttpMessage.h"

namespace cg::cli::http {
namespace {

HeadParse parse(const std::string& bytes, Request& req, const Limits& limits = {})
{
    return parseRequestHead(bytes, limits, req);
}

TEST(HttpMessage, ParsesARequestHeadWithItsPathQueryAndHeaders)
{
    Request req;
    const std::string head =
        "GET /api/preview?node=a%20b&port=im+age&node=second HTTP/1.1\r\n"
        "Host: 127.0.0.1:8642\r\nX-Thing:  spaced value \t\r\n\r\nBODY";
    const HeadParse p = parse(head, req);
    ASSERT_EQ(p.state, HeadParse::State::Complete) << p.reason;
    EXPECT_EQ(p.headBytes, head.size() - 4);
    EXPECT_EQ(req.method, "GET");
    EXPECT_EQ(req.path, "/api/preview");
    EXPECT_EQ(req.query.at("node"), "a b");  // the first of a repeated name
    EXPECT_EQ(req.query.at("port"), "im age");
    EXPECT_EQ(req.headerOr("host"), "127.0.0.1:8642");
    EXPECT_EQ(req.headerOr("x-thing"), "spaced value");
    EXPECT_EQ(req.header("content-length"), nullptr);
}

TEST(HttpMessage, IsIncompleteUntilTheBlankLineArrives)
{
    const std::string head = "POST /api/param HTTP/1.1\r\nContent-Length: 5\r\n\r\n";
    for (std::size_t n = 0; n < head.size(); ++n) {
        Request req;
        EXPECT_EQ(parse(head.substr(0, n), req).state, HeadParse::State::Incomplete) << n;
    }
    Request req;
    const HeadParse p = parse(head, req);
    ASSERT_EQ(p.state, HeadParse::State::Complete);
    EXPECT_EQ(req.contentLength, 5u);
    // Bare LF line ends are read as CRLF ones.
    EXPECT_EQ(parse("GET / HTTP/1.0\nHost: x\n\n", req).state, HeadParse::State::Complete);
}

TEST(HttpMessage, RefusesAHeadLargerThanTheLimitBeforeItEnds)
{
    Limits limits;
    limits.maxHeadBytes = 1024;
    std::string head = "GET / HTTP/1.1\r\n";
    while (head.size() <= limits.maxHeadBytes) head += "X-Pad: aaaaaaaaaaaaaaaa\r\n";
    Request req;
    const HeadParse p = parse(head, req, limits);  // no blank line yet: refused all the same
    EXPECT_EQ(p.state, HeadParse::State::Refused);
    EXPECT_EQ(p.status, 431);
    // Exactly at the limit is accepted.
    std::string fits = "GET / HTTP/1.1\r\nX: ";
    fits += std::string(limits.maxHeadBytes - fits.size() - 4, 'a') + "\r\n\r\n";
    ASSERT_EQ(fits.size(), limits.maxHeadBytes);
    EXPECT_EQ(parse(fits, req, limits).state, HeadParse::State::Complete);
}

TEST(HttpMessage, RefusesMoreHeaderLinesThanTheLimit)
{
    Limits limits;
    limits.maxHeaders = 3;
    Request req;
    EXPECT_EQ(parse("GET / HTTP/1.1\r\nA: 1\r\nB: 2\r\nC: 3\r\n\r\n", req, limits).state,
              HeadParse::State::Complete);
    const HeadParse p =
        parse("GET / HTTP/1.1\r\nA: 1\r\nB: 2\r\nC: 3\r\nD: 4\r\n\r\n", req, limits);
    EXPECT_EQ(p.status, 431);
}

TEST(HttpMessage, BodiesAreFramedByOneContentLengthWithinTheLimit)
{
    Limits limits;
    limits.maxBodyBytes = 100;
    const auto statusOf = [&](const std::string& headers) {
        Request req;
        return parse("POST /api/save HTTP/1.1\r\n" + headers + "\r\n", req, limits).status;
    };
    EXPECT_EQ(statusOf("Content-Length: 100\r\n"), 0);
    EXPECT_EQ(statusOf("Content-Length: 101\r\n"), 413);
    EXPECT_EQ(statusOf("Content-Length: 99999999999999999999999999\r\n"), 413);
    EXPECT_EQ(statusOf("Content-Length: -1\r\n"), 400);
    EXPECT_EQ(statusOf("Content-Length: 1x\r\n"), 400);
    EXPECT_EQ(statusOf("Content-Length: \r\n"), 400);
    EXPECT_EQ(statusOf("Content-Length: 5\r\nContent-Length: 6\r\n"), 400);
    EXPECT_EQ(statusOf("Content-Length: 5\r\nContent-Length: 5\r\n"), 0);
    EXPECT_EQ(statusOf("Transfer-Encoding: chunked\r\n"), 501);
}

TEST(HttpMessage, RefusesMalformedRequestLinesAndHeaders)
{
    for (const char* head : {
             "GET /\r\n\r\n",                         // no version
             "GET  / HTTP/1.1\r\n\r\n",               // two spaces
             "GET http://evil/ HTTP/1.1\r\n\r\n",     // absolute form
             "GET * HTTP/1.1\r\n\r\n",                // asterisk form
             "G(T / HTTP/1.1\r\n\r\n",                // not a token
             "GET /a%zz HTTP/1.1\r\n\r\n",            // bad escape
             "GET /a%00b HTTP/1.1\r\n\r\n",           // NUL in the path
             "GET /a?x=%4 HTTP/1.1\r\n\r\n",          // truncated escape
             "GET / HTTP/1.1\r\nNo colon\r\n\r\n",    // header without a colon
             "GET / HTTP/1.1\r\n folded: x\r\n\r\n",  // obsolete line folding
             "GET / HTTP/1.1\r\nA b: x\r\n\r\n",      // space in a name
             "GET / HTTP/1.1\r\nA: x\x01y\r\n\r\n",   // control character in a value
             "\r\n\r\n",                              // no request line
         }) {
        Request req;
        const HeadParse p = parse(head, req);
        EXPECT_EQ(p.state, HeadParse::State::Refused) << head;
        EXPECT_EQ(p.status, 400) << head;
    }
    Request req;
    EXPECT_EQ(parse("GET / HTTP/2.0\r\n\r\n", req).status, 505);
    // Junk that cannot begin a request line is refused without waiting for a line end.
    EXPECT_EQ(parse("\x16\x03\x01", req).status, 400);  // a TLS ClientHello
}

TEST(HttpMessage, PercentEncodingRoundTrips)
{
    const std::string text = "a b/c?d&e=f%g+h~i.j_k-l\xc3\xa9";
    std::string back;
    ASSERT_TRUE(percentDecode(percentEncode(text), true, back));
    EXPECT_EQ(back, text);
    EXPECT_EQ(percentEncode("render.1"), "render.1");
    EXPECT_EQ(percentEncode("a&b"), "a%26b");
}

TEST(HttpMessage, ARepliesFramingIsItsContentLengthAndClose)
{
    Response res;
    res.status = 409;
    res.body = "{\"error\":\"x\"}";
    res.headers.emplace_back("Cache-Control", "no-store");
    const std::string wire = serializeResponse(res);
    EXPECT_EQ(wire.rfind("HTTP/1.1 409 Conflict\r\n", 0), 0u) << wire;
    EXPECT_NE(wire.find("Content-Length: 13\r\n"), std::string::npos);
    EXPECT_NE(wire.find("Connection: close\r\n"), std::string::npos);
    EXPECT_NE(wire.find("Cache-Control: no-store\r\n"), std::string::npos);
    EXPECT_EQ(wire.substr(wire.size() - res.body.size()), res.body);
}

}  // namespace
}  // namespace cg::cli::http
