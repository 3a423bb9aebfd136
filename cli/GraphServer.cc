#include "cli/GraphServer.h"

#include <httplib.h>
#include <sys/socket.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "algo/render/Display.h"
#include "cli/PreviewPicture.h"
#include "core/Error.h"
#include "core/NodeDeclJson.h"
#include "formats/PngFile.h"
#include "nodes/render/ImageFile.h"

namespace cg::cli {

namespace {

/// Request bodies are small JSON edits; anything larger is refused (413) before it is read.
constexpr std::size_t kMaxBodyBytes = 1u << 20;
/// How often the graph file is looked at for a change made outside the page.
constexpr std::chrono::milliseconds kWatchInterval{300};
/// How often stop() looks whether the server has begun to run.
constexpr std::chrono::milliseconds kStopPoll{5};

void replyJson(httplib::Response& res, int status, const nlohmann::json& body)
{
    res.status = status;
    res.set_content(body.dump(), "application/json");
}

void replyError(httplib::Response& res, int status, const std::string& message)
{
    replyJson(res, status, {{"error", message}});
}

/// The request's body as a JSON object; nullopt after replying 400 when it is not one.
std::optional<nlohmann::json> jsonBody(const httplib::Request& req, httplib::Response& res)
{
    nlohmann::json body = nlohmann::json::parse(req.body, nullptr, /*allow_exceptions=*/false);
    if (body.is_discarded() || !body.is_object()) {
        replyError(res, 400, "the request body must be a JSON object");
        return std::nullopt;
    }
    return body;
}

/// body[key] as a string; nullopt after replying 400 when it is missing or not one.
std::optional<std::string> stringField(const nlohmann::json& body, const char* key,
                                       httplib::Response& res)
{
    const auto it = body.find(key);
    if (it == body.end() || !it->is_string()) {
        replyError(res, 400, std::string("'") + key + "' must be a string");
        return std::nullopt;
    }
    return it->get<std::string>();
}

/// Why a request may not come from this server's own page, or "" when it may. Any web page
/// the user opens could send requests to a server on 127.0.0.1 (cross-site request forgery)
/// or reach it through a name of its own that resolves there (DNS rebinding); the page's
/// edits, cooks and saves must come from the page itself, as development servers such as
/// Vite's and Jupyter's require:
/// - the Host header names this server (a loopback name and the port) when it listens on a
///   loopback address;
/// - a POST is JSON (a cross-site JSON POST needs a CORS preflight, which is never granted)
///   and, when it says where it comes from (Origin), it comes from this server.
std::string refusal(const httplib::Request& req, const std::string& host, int port)
{
    const std::string hostHeader = req.get_header_value("Host");
    const std::string suffix = ":" + std::to_string(port);
    const bool loopback = host == "127.0.0.1" || host == "localhost" || host == "::1";
    if (loopback) {
        bool named = false;
        for (const char* name : {"127.0.0.1", "localhost", "[::1]"})
            named = named || hostHeader == name + suffix;
        if (!named) return "Host '" + hostHeader + "' is not this server";
    }
    if (req.method != "POST") return "";
    if (req.get_header_value("Content-Type").rfind("application/json", 0) != 0)
        return "a POST must be JSON (Content-Type: application/json)";
    if (req.has_header("Origin") && req.get_header_value("Origin") != "http://" + hostHeader)
        return "Origin '" + req.get_header_value("Origin") + "' is not this server's page";
    return "";
}

/// The files beside the graph file (in its folder and up to kFileListDepth folders below,
/// hidden ones left out, at most kFileListMax), as relative paths: what an input-file
/// parameter may name, offered by the page as suggestions.
constexpr int kFileListDepth = 3;
constexpr std::size_t kFileListMax = 1000;

std::vector<std::string> filesBeside(const std::filesystem::path& graphFile)
{
    namespace fs = std::filesystem;
    const fs::path dir = graphFile.parent_path().empty() ? fs::path(".") : graphFile.parent_path();
    std::vector<std::string> files;
    std::error_code ec;
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    for (; !ec && it != fs::recursive_directory_iterator() && files.size() < kFileListMax;
         it.increment(ec)) {
        const bool hidden = it->path().filename().string().rfind('.', 0) == 0;
        if (it->is_directory(ec) && (hidden || it.depth() + 1 >= kFileListDepth)) {
            it.disable_recursion_pending();
            continue;
        }
        if (!hidden && it->is_regular_file(ec))
            files.push_back(it->path().lexically_relative(dir).generic_string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

/// The writers downstream of `node` that cook frame by frame (not those that gather every
/// frame, such as EncodeVideo).
std::vector<std::string> writersBelow(const Graph& graph, const std::string& node)
{
    const std::size_t from = graph.indexOf(node);
    std::vector<bool> below(graph.nodes().size(), false);
    below[from] = true;
    std::vector<std::string> writers;
    for (const std::size_t i : graph.topologicalOrder()) {
        for (const std::size_t up : graph.upstream()[i]) below[i] = below[i] || below[up];
        const NodeDecl& decl = *graph.nodes()[i].decl;
        if (i != from && below[i] && decl.writesFiles && !decl.gathersFrames)
            writers.push_back(graph.nodes()[i].id);
    }
    return writers;
}

/// How the page shows `node`'s image output `port`: as the WriteImage it feeds writes its PNG
/// of `frame` (exposure, tone map, dither), or with WriteImage's defaults when none does.
algo::DisplaySettings previewDisplay(const Graph& graph, const std::string& node,
                                     const std::string& port, int frame)
{
    for (const GraphNode& n : graph.nodes()) {
        const auto in = n.inputs.find("image");
        if (n.decl->type == "WriteImage" && in != n.inputs.end() && in->second.node == node &&
            in->second.port == port)
            return writeImageDisplay(n.params, frame);
    }
    algo::DisplaySettings display;
    display.seed = static_cast<std::uint64_t>(frame);
    return display;
}

}  // namespace

GraphServer::GraphServer(const Registry& registry, ServeOptions options)
    : mOptions(std::move(options)), mRegistry(registry),
      mServer(std::make_unique<httplib::Server>()),
      mDoc(GraphDocument::load(mOptions.graphFile, registry, mOptions.load))
{
    for (const std::string& assignment : mOptions.sets) mDoc->applySetOverride(assignment);
    mDoc->completeGraph();  // a graph the CLI would refuse is refused here too
    mFileText = mDoc->fileText();
    mServer->set_payload_max_length(kMaxBodyBytes);
    // One request a connection: a browser that reuses a kept-alive connection the server has
    // just timed out sees its POST fail ("Failed to fetch"); on this machine's loopback a new
    // connection costs nothing.
    mServer->set_keep_alive_max_count(1);
    mServer->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        const std::string why = refusal(req, mOptions.host, mPort.load());
        if (why.empty()) return httplib::Server::HandlerResponse::Unhandled;
        replyError(res, 403, why);
        return httplib::Server::HandlerResponse::Handled;
    });
    mServer->set_socket_options([this](socket_t sock) {
        httplib::default_socket_options(sock);
        mListenSocket = sock;
    });
    routes();
}

GraphServer::~GraphServer() = default;

int GraphServer::bind()
{
    const int port = mOptions.port == 0 ? mServer->bind_to_any_port(mOptions.host)
                                        : (mServer->bind_to_port(mOptions.host, mOptions.port)
                                               ? mOptions.port
                                               : -1);
    if (port < 0)
        throw InputError("--port " + std::to_string(mOptions.port),
                         "cannot listen on " + mOptions.host + ":" +
                             std::to_string(mOptions.port) + " (in use?)");
    // Debian's built cpp-httplib listens with a backlog of 5: a page's burst of requests
    // beyond it waits a second for a SYN retry, or fails. Listening again sets a longer one.
    if (mListenSocket >= 0) ::listen(mListenSocket, SOMAXCONN);
    mPort = port;
    return port;
}

void GraphServer::listen()
{
    std::thread watcher([this] { watchFile(); });
    mServer->listen_after_bind();
    mListenEnded = true;
    {
        std::lock_guard<std::mutex> lock(mStopMutex);
        mStopping = true;
    }
    mStopped.notify_all();
    watcher.join();
}

void GraphServer::stop()
{
    mDoc->cancel();
    // httplib's stop() does nothing until the server runs: a signal that comes between bind()
    // and listen() would be lost and listen() would never return. Wait for it to run.
    while (!mServer->is_running() && !mListenEnded) std::this_thread::sleep_for(kStopPoll);
    mServer->stop();
}

void GraphServer::edit(httplib::Response& res, const std::function<void(GraphDocument&)>& change)
{
    try {
        std::lock_guard<std::mutex> lock(mDocMutex);
        change(*mDoc);
    } catch (const InputError& e) {
        return replyError(res, 400, e.what());
    }
    changed();
    replyJson(res, 200, {{"version", mVersion.load()}});
}

void GraphServer::watchFile()
{
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(mStopMutex);
            if (mStopped.wait_for(lock, kWatchInterval, [this] { return mStopping; })) return;
        }
        // Read before taking the document, so that edits and cooks do not wait on the disk.
        std::optional<std::string> text;
        std::string error;
        try {
            text = readGraphText(mOptions.graphFile, mOptions.load);
        } catch (const InputError& e) {
            error = e.what();  // gone, unreadable or too large
        }
        std::lock_guard<std::mutex> lock(mDocMutex);
        if (text) {
            if (*text == mFileText) continue;  // as last loaded (or refused)
            mFileText = *text;
            try {
                mDoc->reload(*text);
            } catch (const InputError& e) {
                error = e.what();
            }
        } else {
            mFileText.clear();  // the file coming back is loaded again, even unchanged
            if (error == mFileError) continue;
        }
        mFileError = error;  // the page says why; on an error it keeps the graph it has
        changed();
    }
}

void GraphServer::routes()
{
    httplib::Server& s = *mServer;
    if (!s.set_mount_point("/", mOptions.webDir.string()))
        throw InputError(mOptions.webDir.string(), "the page's folder does not exist");

    // The graph, the declarations of the node types it uses, and every type's name.
    s.Get("/api/graph", [this](const httplib::Request&, httplib::Response& res) {
        nlohmann::json types = nlohmann::json::object();
        nlohmann::json graph;
        std::string fileError;
        {
            std::lock_guard<std::mutex> lock(mDocMutex);
            graph = mDoc->json();
            fileError = mFileError;
            for (const GraphNode& n : mDoc->graph().nodes())
                types[n.decl->type] = nodeDeclToJson(*n.decl);
        }
        nlohmann::json all = nlohmann::json::array();
        for (const NodeDecl* d : mRegistry.nodes()) all.push_back(d->type);
        replyJson(res, 200,
                  {{"file", mOptions.graphFile.filename().string()},
                   {"graph", graph},
                   {"types", types},
                   {"registry", all},
                   {"version", mVersion.load()},
                   {"fileError", fileError}});
    });

    s.Get("/api/version", [this](const httplib::Request&, httplib::Response& res) {
        std::lock_guard<std::mutex> lock(mDocMutex);
        replyJson(res, 200, {{"version", mVersion.load()}, {"fileError", mFileError}});
    });

    // The files an input-file parameter may name, relative to the graph.
    s.Get("/api/files", [this](const httplib::Request&, httplib::Response& res) {
        replyJson(res, 200, {{"files", filesBeside(mOptions.graphFile)}});
    });

    // Wiring edits (nodes added or deleted, inputs connected or not): the page sends the
    // whole edited graph, loaded with the same type checks as a file.
    s.Post("/api/graph", [this](const httplib::Request& req, httplib::Response& res) {
        const auto body = jsonBody(req, res);
        if (!body) return;
        if (!body->contains("graph") || !body->at("graph").is_object())
            return replyError(res, 400, "'graph' must be a graph's JSON object");
        edit(res, [&](GraphDocument& doc) { doc.replace(body->at("graph").dump()); });
    });

    // One parameter, checked as `--set` and loading check it: 400 with the CLI's message.
    s.Post("/api/param", [this](const httplib::Request& req, httplib::Response& res) {
        const auto body = jsonBody(req, res);
        if (!body) return;
        const auto node = stringField(*body, "node", res);
        if (!node) return;
        const auto param = stringField(*body, "param", res);
        if (!param) return;
        if (!body->contains("value")) return replyError(res, 400, "'value' is missing");
        edit(res, [&](GraphDocument& doc) { doc.setParam(*node, *param, body->at("value")); });
    });

    // Cooks one output at a frame, with what it needs that the last cooks did not make.
    s.Post("/api/cook", [this](const httplib::Request& req, httplib::Response& res) {
        const auto body = jsonBody(req, res);
        if (!body) return;
        const auto node = stringField(*body, "node", res);
        if (!node) return;
        const auto port = body->contains("port") ? stringField(*body, "port", res)
                                                  : std::optional<std::string>("image");
        if (!port) return;
        const auto frame = body->find("frame");
        if (frame == body->end() || !frame->is_number_integer())
            return replyError(res, 400, "'frame' must be an integer");
        // With "write": true the writers below the node write this frame's files too.
        const auto write = body->find("write");
        if (write != body->end() && !write->is_boolean())
            return replyError(res, 400, "'write' must be true or false");
        Graph graph;
        try {
            std::lock_guard<std::mutex> lock(mDocMutex);
            graph = mDoc->completeGraph();
        } catch (const InputError& e) {
            return replyError(res, 400, e.what());
        }
        const int f = frame->get<int>();
        if (f < graph.frames.start || f > graph.frames.end)
            return replyError(res, 400,
                              "frame " + std::to_string(f) + " is outside the graph's frames " +
                                  std::to_string(graph.frames.start) + ":" +
                                  std::to_string(graph.frames.end));
        const auto started = std::chrono::steady_clock::now();
        DataPtr value;
        try {
            const bool writes = write != body->end() && write->get<bool>() && graph.find(*node);
            value = mDoc->cook(graph, *node, *port, f, mOptions.cacheDir, mOptions.outDir,
                               writes ? writersBelow(graph, *node) : std::vector<std::string>{});
        } catch (const InputError& e) {
            return replyError(res, 400, e.what());
        } catch (const CookError& e) {
            return replyError(res, e.inputFault() ? 400 : 500, e.what());
        } catch (const Cancelled&) {
            return replyError(res, 409, "cancelled; nothing partial was cached");
        } catch (const CookInProgress& e) {
            return replyError(res, 409, e.what());
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        nlohmann::json reply = {{"report", nlohmann::json::parse(mDoc->lastReport())},
                                {"seconds", seconds}};
        if (auto picture = previewPicture(value, previewDisplay(graph, *node, *port, f))) {
            std::string png = formats::encodePngRgb8(picture->width, picture->height, picture->rgb);
            std::lock_guard<std::mutex> lock(mPreviewMutex);
            mPreviews[*node + "." + *port] = std::move(png);
            reply["preview"] = "/api/preview?node=" + *node + "&port=" + *port;
        }
        replyJson(res, 200, reply);
    });

    // Where the cook under way stands: the page's progress bar polls it.
    s.Get("/api/progress", [this](const httplib::Request&, httplib::Response& res) {
        const CookProgress p = mDoc->progress();
        replyJson(res, 200,
                  {{"cooking", p.cooking},
                   {"done", p.done},
                   {"total", p.total},
                   {"seconds", p.seconds},
                   {"finished", p.finished}});
    });

    s.Post("/api/cancel", [this](const httplib::Request&, httplib::Response& res) {
        mDoc->cancel();
        replyJson(res, 200, {{"ok", true}});
    });

    s.Get("/api/preview", [this](const httplib::Request& req, httplib::Response& res) {
        std::lock_guard<std::mutex> lock(mPreviewMutex);
        const std::string port = req.has_param("port") ? req.get_param_value("port") : "image";
        const auto it = mPreviews.find(req.get_param_value("node") + "." + port);
        if (it == mPreviews.end()) return replyError(res, 404, "no preview of that node yet");
        res.set_header("Cache-Control", "no-store");
        res.set_content(it->second, "image/png");
    });

    // Writes the edited graph back to its file, atomically.
    s.Post("/api/save", [this](const httplib::Request&, httplib::Response& res) {
        try {
            std::lock_guard<std::mutex> lock(mDocMutex);
            mFileText = mDoc->save(mOptions.graphFile);  // not a change from outside
        } catch (const InputError& e) {
            return replyError(res, 400, e.what());
        }
        replyJson(res, 200, {{"saved", mOptions.graphFile.string()}});
    });
}

}  // namespace cg::cli
