#pragma once
/// A small HTTP/1.1 server for `cloudgraph serve`, built to stay usable when some of its
/// clients are hostile or slow. One thread owns every socket and reads and writes without
/// blocking, so a client that sends its request a byte at a time, or never reads its reply,
/// holds no worker; each request must arrive whole within a deadline, its head within
/// Limits::maxHeadBytes and its body within Limits::maxBodyBytes. Complete requests go to a
/// pool of workers that run the handler; their replies go back to the socket thread. Every
/// reply closes its connection.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cli/http/HttpMessage.h"

namespace cg::cli::http {

struct ServerOptions {
    Limits limits;
    int workers = 8;  ///< threads running the handler
    /// Connections open at once; past it the one that has waited longest for its request to
    /// arrive is closed to make room (a slow client cannot crowd out the page).
    std::size_t maxConnections = 128;
    std::chrono::milliseconds requestDeadline{10000};  ///< from accept to the whole request
    std::chrono::milliseconds replyDeadline{30000};    ///< to write the whole reply
};

class Server {
public:
    using Handler = std::function<Response(const Request&)>;

    Server(Handler handler, ServerOptions options = {});
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    /// Listens on `host` (a name or a numeric IPv4 or IPv6 address) and `port` (0: any free
    /// one); returns the port. Throws std::runtime_error saying why it cannot.
    int bind(const std::string& host, int port);
    /// Serves until stop(); returns at once when bind() has not succeeded.
    void run();
    /// Makes run() return (from any thread, before or during run()): no new request is
    /// handled, the workers finish the handlers under way.
    void stop();

private:
    struct Connection;
    struct Finished {
        int fd;
        std::string bytes;
    };

    void workerLoop();
    void wake();
    void acceptAll(std::vector<Connection>& connections);
    /// Reads what `c` has sent; returns false when it is to be closed now.
    bool readFrom(Connection& c);
    /// Writes what `c` still has to send; returns false when it is broken.
    bool writeTo(Connection& c);
    /// Reads and drops what `c` sends after its reply; returns false once it has closed.
    bool drain(Connection& c);
    void collectFinished(std::vector<Connection>& connections);

    Handler mHandler;
    ServerOptions mOptions;
    int mListenFd = -1;
    int mWakeFd = -1;  ///< an eventfd: workers and stop() wake the socket thread
    std::atomic<bool> mStopping{false};

    std::mutex mQueueMutex;
    std::condition_variable mQueueReady;
    std::deque<std::pair<int, Request>> mQueue;  ///< complete requests, by socket
    std::vector<Finished> mFinished;             ///< replies the workers have made
    std::vector<std::thread> mWorkers;
};

}  // namespace cg::cli::http
