#include "cli/http/HttpServer.h"

#include <netdb.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace cg::cli::http {

namespace {

using Clock = std::chrono::steady_clock;

/// Bytes read from a socket at a time.
constexpr std::size_t kReadChunk = 16 * 1024;
/// The socket thread looks at deadlines at least this often.
constexpr int kMaxPollMs = 1000;
/// How long a connection whose reply is sent may keep sending before it is closed.
constexpr std::chrono::milliseconds kDrainDeadline{2000};

Response errorResponse(int status, const std::string& message)
{
    Response r;
    r.status = status;
    r.body = nlohmann::json{{"error", message}}.dump(-1, ' ', false,
                                                     nlohmann::json::error_handler_t::replace);
    return r;
}

}  // namespace

struct Server::Connection {
    /// Draining: the reply is sent; what the client still sends is read and dropped until
    /// it closes, so that closing does not reset a connection whose reply is unread (a
    /// client still sending a refused body would lose the refusal).
    enum class State { Reading, Handling, Writing, Draining };
    int fd = -1;
    State state = State::Reading;
    Clock::time_point deadline;
    Clock::time_point accepted;
    std::string received;
    Request request;
    bool headParsed = false;
    std::string reply;
    std::size_t written = 0;

    void startReply(std::string bytes, std::chrono::milliseconds within)
    {
        state = State::Writing;
        reply = std::move(bytes);
        written = 0;
        deadline = Clock::now() + within;
        received = std::string();  // no longer needed: give its memory back now
    }
};

Server::Server(Handler handler, ServerOptions options)
    : mHandler(std::move(handler)),
      mOptions(options),
      mWakeFd(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK))
{
    if (mWakeFd < 0) throw std::runtime_error(std::string("eventfd: ") + std::strerror(errno));
}

Server::~Server()
{
    stop();
    for (std::thread& t : mWorkers)
        if (t.joinable()) t.join();
    if (mListenFd >= 0) ::close(mListenFd);
    ::close(mWakeFd);
}

int Server::bind(const std::string& host, int port)
{
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    addrinfo* found = nullptr;
    if (const int rc = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found))
        throw std::runtime_error("cannot resolve '" + host + "': " + ::gai_strerror(rc));
    std::string why = "no address";
    for (const addrinfo* a = found; a && mListenFd < 0; a = a->ai_next) {
        const int fd =
            ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, a->ai_protocol);
        if (fd < 0) continue;
        const int on = 1;
        ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
        if (::bind(fd, a->ai_addr, a->ai_addrlen) == 0 && ::listen(fd, SOMAXCONN) == 0) {
            mListenFd = fd;
        } else {
            why = std::strerror(errno);
            ::close(fd);
        }
    }
    ::freeaddrinfo(found);
    if (mListenFd < 0) throw std::runtime_error(why);
    sockaddr_storage bound{};
    socklen_t length = sizeof bound;
    ::getsockname(mListenFd, reinterpret_cast<sockaddr*>(&bound), &length);
    return bound.ss_family == AF_INET6
               ? ntohs(reinterpret_cast<const sockaddr_in6*>(&bound)->sin6_port)
               : ntohs(reinterpret_cast<const sockaddr_in*>(&bound)->sin_port);
}

void Server::stop()
{
    mStopping = true;
    {
        std::lock_guard<std::mutex> lock(mQueueMutex);
    }
    mQueueReady.notify_all();
    wake();
}

void Server::wake()
{
    const std::uint64_t one = 1;
    [[maybe_unused]] const ssize_t n = ::write(mWakeFd, &one, sizeof one);
}

void Server::workerLoop()
{
    for (;;) {
        std::pair<int, Request> job;
        {
            std::unique_lock<std::mutex> lock(mQueueMutex);
            mQueueReady.wait(lock, [this] { return mStopping || !mQueue.empty(); });
            if (mStopping) return;
            job = std::move(mQueue.front());
            mQueue.pop_front();
        }
        Response response;
        try {
            response = mHandler(job.second);
        } catch (const std::exception& e) {
            response = errorResponse(500, e.what());
        } catch (...) {
            response = errorResponse(500, "unknown error");
        }
        {
            std::lock_guard<std::mutex> lock(mQueueMutex);
            mFinished.push_back({job.first, serializeResponse(response)});
        }
        wake();
    }
}

bool Server::readFrom(Connection& c)
{
    char chunk[kReadChunk];
    const ssize_t n = ::recv(c.fd, chunk, sizeof chunk, MSG_DONTWAIT);
    if (n == 0) return false;  // closed before its request was whole
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    c.received.append(chunk, static_cast<std::size_t>(n));
    if (!c.headParsed) {
        const HeadParse p = parseRequestHead(c.received, mOptions.limits, c.request);
        if (p.state == HeadParse::State::Incomplete) return true;
        if (p.state == HeadParse::State::Refused) {
            c.startReply(serializeResponse(errorResponse(p.status, p.reason)),
                         mOptions.replyDeadline);
            return true;
        }
        c.headParsed = true;
        c.received.erase(0, p.headBytes);
    }
    if (c.received.size() < c.request.contentLength) return true;
    c.received.resize(c.request.contentLength);  // bytes past the body are not a request
    c.request.body = std::move(c.received);
    c.state = Connection::State::Handling;
    {
        std::lock_guard<std::mutex> lock(mQueueMutex);
        mQueue.emplace_back(c.fd, std::move(c.request));
    }
    c.received = std::string();
    mQueueReady.notify_one();
    return true;
}

bool Server::writeTo(Connection& c)
{
    while (c.written < c.reply.size()) {
        const ssize_t n = ::send(c.fd, c.reply.data() + c.written, c.reply.size() - c.written,
                                 MSG_DONTWAIT | MSG_NOSIGNAL);
        if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
        c.written += static_cast<std::size_t>(n);
    }
    ::shutdown(c.fd, SHUT_WR);
    c.state = Connection::State::Draining;
    c.deadline = Clock::now() + kDrainDeadline;
    return true;
}

bool Server::drain(Connection& c)
{
    // One read a turn, as for requests: a client that never stops sending must not hold
    // the thread that serves every other connection.
    char chunk[kReadChunk];
    const ssize_t n = ::recv(c.fd, chunk, sizeof chunk, MSG_DONTWAIT);
    if (n == 0) return false;
    return n > 0 || errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
}

void Server::acceptAll(std::vector<Connection>& connections)
{
    for (;;) {
        const int fd = ::accept4(mListenFd, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
        if (fd < 0) return;
        if (connections.size() >= mOptions.maxConnections) {
            // Make room by closing the connection that has waited longest for its request.
            auto oldest = connections.end();
            for (auto it = connections.begin(); it != connections.end(); ++it)
                if ((it->state == Connection::State::Reading ||
                     it->state == Connection::State::Draining) &&
                    (oldest == connections.end() || it->accepted < oldest->accepted))
                    oldest = it;
            if (oldest == connections.end()) {
                ::close(fd);  // every slot holds a request under way: refuse this one
                continue;
            }
            ::close(oldest->fd);
            connections.erase(oldest);
        }
        Connection c;
        c.fd = fd;
        c.accepted = Clock::now();
        c.deadline = c.accepted + mOptions.requestDeadline;
        connections.push_back(std::move(c));
    }
}

void Server::collectFinished(std::vector<Connection>& connections)
{
    std::uint64_t count = 0;
    [[maybe_unused]] const ssize_t n = ::read(mWakeFd, &count, sizeof count);
    std::vector<Finished> finished;
    {
        std::lock_guard<std::mutex> lock(mQueueMutex);
        finished.swap(mFinished);
    }
    for (Finished& f : finished)
        for (Connection& c : connections)
            if (c.fd == f.fd && c.state == Connection::State::Handling)
                c.startReply(std::move(f.bytes), mOptions.replyDeadline);
}

void Server::run()
{
    if (mListenFd < 0 || mStopping) return;
    for (int i = 0; i < mOptions.workers; ++i) mWorkers.emplace_back([this] { workerLoop(); });
    std::vector<Connection> connections;
    std::vector<pollfd> polled;
    while (!mStopping) {
        polled.assign({{mListenFd, POLLIN, 0}, {mWakeFd, POLLIN, 0}});
        auto next = Clock::now() + std::chrono::milliseconds(kMaxPollMs);
        for (const Connection& c : connections) {
            const int events = c.state == Connection::State::Writing    ? POLLOUT
                               : c.state == Connection::State::Handling ? 0
                                                                        : POLLIN;
            polled.push_back({c.fd, static_cast<short>(events), 0});
            if (c.state != Connection::State::Handling) next = std::min(next, c.deadline);
        }
        const auto wait = std::chrono::ceil<std::chrono::milliseconds>(next - Clock::now());
        const int ready =
            ::poll(polled.data(), polled.size(), static_cast<int>(std::max<long>(0, wait.count())));
        if (ready < 0 && errno != EINTR) break;
        const auto now = Clock::now();
        std::vector<bool> keep(connections.size(), true);
        for (std::size_t i = 0; i < connections.size(); ++i) {
            Connection& c = connections[i];
            const short revents = polled[i + 2].revents;
            if (c.state == Connection::State::Reading && revents)
                keep[i] = readFrom(c);
            else if (c.state == Connection::State::Writing && revents)
                keep[i] = writeTo(c);
            else if (c.state == Connection::State::Draining && revents)
                keep[i] = drain(c);
            if (!keep[i] || c.state == Connection::State::Handling || now < c.deadline) continue;
            if (c.state == Connection::State::Reading)
                c.startReply(serializeResponse(errorResponse(
                                 408, "the request did not arrive within the deadline")),
                             mOptions.replyDeadline);
            else
                keep[i] = false;  // a reply nobody reads, or a client that keeps sending
        }
        std::size_t kept = 0;
        for (std::size_t i = 0; i < connections.size(); ++i) {
            if (!keep[i])
                ::close(connections[i].fd);
            else if (kept++ != i)  // a self-move would empty the connection's buffers
                connections[kept - 1] = std::move(connections[i]);
        }
        connections.resize(kept);
        if (polled[1].revents) collectFinished(connections);
        if (polled[0].revents) acceptAll(connections);
    }
    stop();
    for (std::thread& t : mWorkers) t.join();
    mWorkers.clear();
    for (const Connection& c : connections) ::close(c.fd);
}

}  // namespace cg::cli::http
