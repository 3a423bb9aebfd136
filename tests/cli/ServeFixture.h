#pragma once
// A `cloudgraph serve` process on a free port of 127.0.0.1 serving a small graph, with an
// HTTP client (cpp-httplib, an independent implementation) that sends what the page sends,
// and a raw socket for what no well-behaved client sends.

#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/TestUtil.h"

namespace cg::test {

/// The synthetic cumulus still, small: a SyntheticCumulus, a Renderer and a WriteImage.
inline const char* kServeGraph = R"({
  "cloudgraph": 1,
  "frames": {"start": 0, "end": 2},
  "nodes": {
    "cloud": {"type": "SyntheticCumulus", "params": {"voxelSize": 40, "baseRadius": 500}},
    "render": {"type": "Renderer", "inputs": {"volume": "cloud.volume"},
               "params": {"width": 64, "height": 48, "cameraPosition": [400, -3800, 700]}},
    "write": {"type": "WriteImage", "inputs": {"image": "render.image"},
              "params": {"file": "still.####.png"}}
  }
})";

/// A socket connected to 127.0.0.1:port (-1 when it cannot connect), closed with the object.
class RawConnection {
public:
    explicit RawConnection(int port)
    {
        mFd = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_port = htons(static_cast<std::uint16_t>(port));
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::connect(mFd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
            ::close(mFd);
            mFd = -1;
        }
        const timeval timeout{20, 0};  // no test waits forever on a server that hangs
        ::setsockopt(mFd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    }
    ~RawConnection()
    {
        if (mFd >= 0) ::close(mFd);
    }
    RawConnection(const RawConnection&) = delete;
    RawConnection& operator=(const RawConnection&) = delete;

    bool connected() const { return mFd >= 0; }
    /// Sends all of `bytes`; false when the server has closed or reset the connection.
    bool send(const std::string& bytes)
    {
        for (std::size_t at = 0; at < bytes.size();) {
            const ssize_t n = ::send(mFd, bytes.data() + at, bytes.size() - at, MSG_NOSIGNAL);
            if (n <= 0) return false;
            at += static_cast<std::size_t>(n);
        }
        return true;
    }
    /// Everything the server sends until it closes (or 20 s pass).
    std::string receiveAll()
    {
        std::string all;
        char chunk[4096];
        for (ssize_t n; (n = ::recv(mFd, chunk, sizeof chunk, 0)) > 0;)
            all.append(chunk, static_cast<std::size_t>(n));
        return all;
    }

private:
    int mFd = -1;
};

/// The status code of a raw reply ("HTTP/1.1 431 ..." -> 431), or 0.
inline int statusOf(const std::string& reply)
{
    return reply.rfind("HTTP/1.", 0) == 0 && reply.size() > 12 ? std::stoi(reply.substr(9, 3)) : 0;
}

class ServeTest : public ::testing::Test {
protected:
    virtual const char* graphText() const { return kServeGraph; }
    /// Options of `serve` besides the graph, --port 0, --out and --cache.
    virtual std::vector<std::string> extraArgs() const { return {}; }

    void SetUp() override
    {
        test::writeFile(graphFile(), graphText());
        std::filesystem::create_directories(dir / "out");
        std::vector<std::string> args = {
            "serve", graphFile().string(),   "--port",  "0",
            "--out", (dir / "out").string(), "--cache", (dir / "cache").string()};
        for (const std::string& a : extraArgs()) args.push_back(a);
        server = std::make_unique<CliProcess>(args);
        // The first line names the URL with the port the system chose.
        const std::regex url(R"(http://(\S+):(\d+)/)");
        std::smatch m;
        for (int i = 0; i < 200 && port == 0; ++i) {
            const std::string out = server->outputSoFar();
            if (std::regex_search(out, m, url))
                port = std::stoi(m[2]);
            else
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        ASSERT_NE(port, 0) << "the server printed no URL";
        // The page carries the session's token; every POST the page makes sends it back.
        httplib::Client c("127.0.0.1", port);
        const auto page = c.Get("/");
        ASSERT_TRUE(page);
        const std::regex meta(R"re(name="cloudgraph-token" content="([0-9a-f]{32})")re");
        ASSERT_TRUE(std::regex_search(page->body, m, meta)) << "no token in the page";
        token = m[1];
    }

    std::filesystem::path graphFile() const { return dir / "graph.json"; }
    /// Replaces the graph file as an editor's save does: whole, by a rename.
    void editFile(const std::string& text) const
    {
        test::writeFile(dir / "graph.json.new", text);
        std::filesystem::rename(dir / "graph.json.new", graphFile());
    }
    httplib::Client client() const
    {
        httplib::Client c("127.0.0.1", port);
        c.set_read_timeout(60, 0);
        return c;
    }
    /// A POST as the page sends it: with the session's token (and `headers`).
    httplib::Result postText(const std::string& path, const std::string& body,
                             const std::string& type = "application/json",
                             httplib::Headers headers = {}) const
    {
        headers.emplace("X-CloudGraph-Token", token);
        // cpp-httplib 0.11 leaves Host out when it is given headers; a browser always sends it.
        if (headers.find("Host") == headers.end())
            headers.emplace("Host", "127.0.0.1:" + std::to_string(port));
        return client().Post(path.c_str(), headers, body, type.c_str());
    }
    httplib::Result post(const std::string& path, const nlohmann::json& body) const
    {
        return postText(path, body.dump());
    }

    TempDir dir;
    std::unique_ptr<CliProcess> server;
    int port = 0;
    std::string token;
};

}  // namespace cg::test
