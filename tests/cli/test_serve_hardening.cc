// `cloudgraph serve` under hostile and careless clients, against the real process on
// 127.0.0.1: bodies and heads built to crash or exhaust it, slow clients, foreign pages, a
// file edited outside the page, and options that cannot work. Each test is bounded in time.

#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/ServeFixture.h"
#include "support/TestUtil.h"

namespace cg {
namespace {

using nlohmann::json;
using test::RawConnection;
using test::ServeTest;
using test::statusOf;

using ServeHardening = ServeTest;

// The body is read by the graph loader's depth-limited parser, never recursed into.
TEST_F(ServeHardening, ADeeplyNestedBodyIsRefusedAndTheServerLives)
{
    const std::size_t depth = 100000;  // 200 KB
    const std::string nested = std::string(depth, '[') + std::string(depth, ']');
    for (const std::string& body :
         {"{\"graph\": {\"x\": " + nested + "}}",
          "{\"node\": \"render\", \"param\": \"fov\", \"value\": " + nested + "}"}) {
        const auto res = postText("/api/graph", body, "application/json");
        ASSERT_TRUE(res) << "the server died";
        EXPECT_EQ(res->status, 400);
        EXPECT_NE(res->body.find("deeper"), std::string::npos) << res->body;
    }
    EXPECT_EQ(client().Get("/api/version")->status, 200);
}

// A syntax error's message quotes the bytes sent, which need not be UTF-8; the reply is still
// JSON (the fuzz target serve_api found it answered 500).
TEST_F(ServeHardening, AReplyQuotingBytesThatAreNotUtf8IsStillJson)
{
    const auto res = postText("/api/cook",
                              "{\"node\": \"render\", \"frame\": 4\xce"
                              "2}");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
    EXPECT_TRUE(json::accept(res->body)) << res->body;
}

// 2^32 + 2 once cooked frame 2 and 2^63 frame 0.
TEST_F(ServeHardening, FrameNumbersAreRangeCheckedBeforeTheyAreNarrowed)
{
    for (const char* frame : {"4294967298", "9223372036854775808", "18446744073709551615",
                              "-4294967296", "-9223372036854775808"}) {
        const std::string body = std::string("{\"node\": \"render\", \"frame\": ") + frame + "}";
        const auto res = postText("/api/cook", body, "application/json");
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 400) << frame;
        EXPECT_NE(res->body.find("outside the graph's frames 0:2"), std::string::npos) << res->body;
    }
}

// A page of another origin cannot read ours, so it cannot learn the token every POST needs.
TEST_F(ServeHardening, APostWithoutTheSessionTokenIsRefused)
{
    httplib::Client bare("127.0.0.1", port);
    const std::string edit = json{{"node", "render"}, {"param", "fov"}, {"value", 12}}.dump();
    for (const httplib::Headers& headers :
         {httplib::Headers{}, httplib::Headers{{"X-CloudGraph-Token", "0123456789abcdef"}},
          httplib::Headers{{"X-CloudGraph-Token", token + "0"}}}) {
        const auto res = bare.Post("/api/param", headers, edit, "application/json");
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 403);
        EXPECT_NE(res->body.find("X-CloudGraph-Token"), std::string::npos) << res->body;
    }
    EXPECT_EQ(bare.Post("/api/save", "{}", "application/json")->status, 403);
    EXPECT_EQ(test::readFile(graphFile()), test::kServeGraph);
    EXPECT_EQ(post("/api/param", json::parse(edit))->status, 200);
}

TEST_F(ServeHardening, AHeadLargerThanTheLimitIsRefusedWith431)
{
    RawConnection c(port);
    ASSERT_TRUE(c.connected());
    std::string head =
        "GET /api/version HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n";
    for (int i = 0; head.size() < (64u << 10); ++i)
        head += "X-Pad-" + std::to_string(i) + ": " + std::string(40, 'a') + "\r\n";
    c.send(head);  // the server may refuse before it has all of it
    EXPECT_EQ(statusOf(c.receiveAll()), 431);
    EXPECT_EQ(client().Get("/api/version")->status, 200);
}

// Clients that drip their request a line at a time hold no worker and cannot crowd the page
// out: with more of them than workers, and more than the server keeps open, the page's
// requests are answered at once; each dripping client is cut off at the request deadline.
TEST_F(ServeHardening, SlowClientsDoNotStarveThePage)
{
    const std::size_t slowCount = 160;  // more than the 8 workers and the 128 connections kept
    std::vector<std::unique_ptr<RawConnection>> slow;
    for (std::size_t i = 0; i < slowCount; ++i) {
        slow.push_back(std::make_unique<RawConnection>(port));
        slow.back()->send("GET /api/version HTTP/1.1\r\n");
    }
    httplib::Client page("127.0.0.1", port);
    page.set_connection_timeout(3, 0);
    page.set_read_timeout(3, 0);
    const auto started = std::chrono::steady_clock::now();
    int answered = 0;
    for (int round = 0; round < 12; ++round) {
        for (auto& s : slow) s->send("X-Drip: " + std::to_string(round) + "\r\n");
        const auto res = page.Get("/api/version");
        answered += res && res->status == 200;
        std::this_thread::sleep_for(std::chrono::milliseconds(1000));
    }
    EXPECT_EQ(answered, 12);
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(40));
    // Past the 10 s deadline every dripping client has been answered (408) or closed.
    for (auto& s : slow) {
        const std::string reply = s->receiveAll();
        EXPECT_TRUE(reply.empty() || statusOf(reply) == 408) << reply.substr(0, 80);
    }
}

// A client refused for its body size that goes on sending (the server drains what it sends
// so that it can read the refusal) holds the socket thread no longer than others.
TEST_F(ServeHardening, AClientThatNeverStopsSendingCannotHoldTheServer)
{
    RawConnection flood(port);
    ASSERT_TRUE(flood.send("POST /api/param HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                           "\r\nContent-Length: 999999999\r\n\r\n"));
    std::atomic<bool> stop{false};
    std::thread sender([&] {
        const std::string chunk(1 << 16, 'x');
        while (!stop && flood.send(chunk)) {
        }
    });
    httplib::Client page("127.0.0.1", port);
    page.set_connection_timeout(3, 0);
    page.set_read_timeout(3, 0);
    int answered = 0;
    for (int i = 0; i < 10; ++i) {
        const auto res = page.Get("/api/version");
        answered += res && res->status == 200;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    stop = true;
    sender.join();
    EXPECT_EQ(answered, 10);
}

TEST_F(ServeHardening, UnknownRoutesAndMethodsAreRefused)
{
    EXPECT_EQ(client().Get("/api/nope")->status, 404);
    EXPECT_EQ(client().Delete("/api/graph")->status, 405);
    EXPECT_EQ(postText("/index.html", "{}", "application/json")->status, 405);
    EXPECT_EQ(client().Get("/.hidden")->status, 404);
}

// An edit made in an editor, even one that does not load, is never replaced without asking.
TEST_F(ServeHardening, SaveRefusesToReplaceAFileChangedOnDisk)
{
    const std::string broken = R"({"cloudgraph": 1, "nodes": {"x": {"type": "Nope"}}})";
    editFile(broken);
    const auto refused = post("/api/save", json::object());
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 409);
    EXPECT_EQ(json::parse(refused->body)["conflict"], true) << refused->body;
    EXPECT_EQ(test::readFile(graphFile()), broken);
    // Asked to, it overwrites: the page's graph, which the CLI loads.
    const auto forced = post("/api/save", {{"overwrite", true}});
    ASSERT_EQ(forced->status, 200) << forced->body;
    EXPECT_EQ(test::runCli({"validate", graphFile().string()}).exitCode, 0);
    EXPECT_EQ(json::parse(client().Get("/api/version")->body)["fileError"], "");
    // A valid edit is either refused or, once the watcher has loaded it, kept by the save.
    json edited = test::readJson(graphFile());
    edited["nodes"]["render"]["params"]["fov"] = 21;
    editFile(edited.dump(2));
    const auto res = post("/api/save", json::object());
    ASSERT_TRUE(res);
    EXPECT_TRUE(res->status == 409 || res->status == 200) << res->status;
    EXPECT_EQ(test::readJson(graphFile())["nodes"]["render"]["params"]["fov"], 21);
    // A graph file removed from under the page is a conflict too.
    std::filesystem::remove(graphFile());
    EXPECT_EQ(post("/api/save", json::object())->status, 409);
    EXPECT_FALSE(std::filesystem::exists(graphFile()));
}

class ServeOnAllAddresses : public ServeTest {
protected:
    std::vector<std::string> extraArgs() const override
    {
        return {"--host", "0.0.0.0", "--allow-host", "studio-box.lan"};
    }
};

// Listening on every address, the server still answers only to its own names: a page whose
// DNS name is rebound to this machine is refused.
TEST_F(ServeOnAllAddresses, TheHostHeaderIsCheckedWhateverTheListenAddress)
{
    const std::string p = ":" + std::to_string(port);
    for (const char* host : {"evil.example", "0.0.0.0", "127.0.0.2", "studio-box.lan.evil.example"})
        EXPECT_EQ(client().Get("/api/graph", {{"Host", host + p}})->status, 403) << host;
    for (const char* host : {"studio-box.lan", "STUDIO-BOX.lan", "localhost", "127.0.0.1"})
        EXPECT_EQ(client().Get("/api/graph", {{"Host", host + p}})->status, 200) << host;
}

/// Runs `serve` with `args` for at most 5 s; its exit status, or -1 if it was still serving.
int serveExitStatus(const std::vector<std::string>& args, std::string* output = nullptr)
{
    test::CliProcess p(args);
    for (int i = 0; i < 50 && p.outputSoFar().find("serving") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const bool serving = p.outputSoFar().find("serving") != std::string::npos;
    p.kill(SIGTERM);
    const test::CliResult r = p.wait();
    if (output) *output = r.output + r.errors;
    return serving ? -1 : r.exitCode;
}

TEST(ServeOptions, ACacheThatCannotBeMadeIsRefusedBeforeServing)
{
    test::TempDir dir;
    test::writeFile(dir / "graph.json", test::kServeGraph);
    test::writeFile(dir / "a-file", "x");
    std::string output;
    EXPECT_EQ(serveExitStatus({"serve", (dir / "graph.json").string(), "--port", "0", "--cache",
                               (dir / "a-file").string()},
                              &output),
              2);
    EXPECT_NE(output.find("a-file"), std::string::npos) << output;
}

TEST(ServeOptions, AnIpv6AddressIsPrintedInBrackets)
{
    test::TempDir dir;
    test::writeFile(dir / "graph.json", test::kServeGraph);
    test::CliProcess p({"serve", (dir / "graph.json").string(), "--port", "0", "--host", "::1"});
    std::string out;
    for (int i = 0; i < 50 && out.find("serving") == std::string::npos; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        out = p.outputSoFar();
    }
    p.kill(SIGTERM);
    const test::CliResult r = p.wait();
    if (out.find("serving") == std::string::npos)
        GTEST_SKIP() << "no IPv6 loopback here: " << r.errors;
    EXPECT_NE(out.find("at http://[::1]:"), std::string::npos) << out;
}

}  // namespace
}  // namespace cg
