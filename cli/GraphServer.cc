#include "cli/GraphServer.h"
#include "cli/ApiBody.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <climits>
#include <exception>
#include <fstream>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "algo/render/image/Display.h"
#include "cli/LastCloudFrame.h"
#include "cli/PaintedMap.h"
#include "cli/PreviewPicture.h"
#include "core/Error.h"
#include "core/NodeDeclJson.h"
#include "formats/PngFile.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/render/ImageFile.h"

namespace cg::cli {

namespace {

/// How often the graph file is looked at for a change made outside the page.
constexpr std::chrono::milliseconds kWatchInterval{300};
/// The page's files are small; a larger one in the web folder is not served.
constexpr std::uintmax_t kMaxPageFileBytes = 16u << 20;
/// The text of index.html that the session's token replaces.
constexpr std::string_view kTokenPlaceholder = "{{CLOUDGRAPH_TOKEN}}";

using http::Request;
using http::Response;

/// Whether two secrets are equal, in a time that does not depend on where they differ.
bool sameSecret(const std::string& a, const std::string& b)
{
    unsigned char differ = a.size() != b.size();
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
        differ |= static_cast<unsigned char>(a[i] ^ b[i]);
    return differ == 0;
}

std::string lowerCase(std::string s)
{
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

/// A name as it appears in a URL and a Host header: an IPv6 address in brackets.
std::string urlHost(const std::string& host)
{
    return host.find(':') != std::string::npos ? "[" + host + "]" : host;
}

/// 128 random bits as hex, from the system's entropy source.
std::string randomToken()
{
    std::random_device entropy;  // libstdc++ reads getrandom() / /dev/urandom
    std::string hex;
    for (int i = 0; i < 4; ++i) {
        char word[9];
        std::snprintf(word, sizeof word, "%08x", static_cast<unsigned>(entropy()));
        hex += word;
    }
    return hex;
}

/// The media type of a page file, by its extension.
std::string contentType(const std::filesystem::path& file)
{
    const std::string ext = file.extension().string();
    if (ext == ".html") return "text/html; charset=utf-8";
    if (ext == ".js") return "text/javascript; charset=utf-8";
    if (ext == ".css") return "text/css; charset=utf-8";
    if (ext == ".png") return "image/png";
    if (ext == ".svg") return "image/svg+xml";
    if (ext == ".json") return "application/json";
    return "application/octet-stream";
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

/// Runs `cook`, turning what a cook throws into the page's reply (400 bad input, 409 cancelled
/// or another cook under way, 500 a failed cook); nullopt when it succeeded.
std::optional<Response> cookFailure(const std::function<void()>& cook)
{
    try {
        cook();
    } catch (const InputError& e) {
        return errorReply(400, e.what());
    } catch (const CookError& e) {
        return errorReply(e.inputFault() ? 400 : 500, e.what());
    } catch (const Cancelled&) {
        return errorReply(409, "cancelled; nothing partial was cached");
    } catch (const CookInProgress& e) {
        return errorReply(409, e.what());
    }
    return std::nullopt;
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
    : mOptions(std::move(options)),
      mRegistry(registry),
      mToken(randomToken()),
      mServer([this](const Request& req) { return handle(req); }),
      mDoc(GraphDocument::load(mOptions.graphFile, registry, mOptions.load))
{
    for (const std::string& assignment : mOptions.sets) mDoc->applySetOverride(assignment);
    mDoc->completeGraph();  // a graph the CLI would refuse is refused here too
    mFileText = mBaseText = mDoc->fileText();
    if (!std::filesystem::is_directory(mOptions.webDir))
        throw InputError(mOptions.webDir.string(), "the page's folder does not exist");
    mRoutes["/api/graph"] = {{"GET", &GraphServer::getGraph}, {"POST", &GraphServer::postGraph}};
    mRoutes["/api/version"] = {{"GET", &GraphServer::getVersion}};
    mRoutes["/api/files"] = {{"GET", &GraphServer::getFiles}};
    mRoutes["/api/param"] = {{"POST", &GraphServer::postParam}};
    mRoutes["/api/cook"] = {{"POST", &GraphServer::postCook}};
    mRoutes["/api/progress"] = {{"GET", &GraphServer::getProgress}};
    mRoutes["/api/cancel"] = {{"POST", &GraphServer::postCancel}};
    mRoutes["/api/preview"] = {{"GET", &GraphServer::getPreview}};
    mRoutes["/api/lastcloud"] = {{"GET", &GraphServer::getLastCloud}};
    mRoutes["/api/save"] = {{"POST", &GraphServer::postSave}};
    mRoutes["/api/paint"] = {{"POST", &GraphServer::postPaint}};
}

GraphServer::~GraphServer() = default;

int GraphServer::bind()
{
    try {
        mPort = mServer.bind(mOptions.host, mOptions.port);
    } catch (const std::runtime_error& e) {
        throw InputError("--host " + mOptions.host + " --port " + std::to_string(mOptions.port),
                         std::string("cannot listen there: ") + e.what());
    }
    return mPort;
}

void GraphServer::listen()
{
    std::thread watcher([this] { watchFile(); });
    mServer.run();
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
    mServer.stop();
}

std::string GraphServer::refusal(const Request& req) const
{
    // Any web page the user opens can send requests to this server (cross-site request
    // forgery) or reach it under a name of its own that resolves here (DNS rebinding). The
    // Host header must name this server, whatever --host is; a POST must be JSON (a
    // cross-site JSON POST needs a CORS preflight, never granted), come from this server's
    // page when it says where it comes from (Origin), and carry the session's token, which
    // only a page of this origin can read.
    const std::string hostHeader = lowerCase(req.headerOr("host"));
    const std::string suffix = ":" + std::to_string(mPort.load());
    std::vector<std::string> names = {"127.0.0.1", "localhost", "[::1]"};
    if (mOptions.host != "0.0.0.0" && mOptions.host != "::")
        names.push_back(lowerCase(urlHost(mOptions.host)));
    bool named = false;
    for (const std::string& name : names) named = named || hostHeader == name + suffix;
    for (const std::string& name : mOptions.allowedHosts)
        named = named || hostHeader == lowerCase(name) || hostHeader == lowerCase(name) + suffix;
    if (!named) return "Host '" + hostHeader + "' is not this server (see serve --allow-host)";
    if (req.method != "POST") return "";
    if (req.headerOr("content-type").rfind("application/json", 0) != 0)
        return "a POST must be JSON (Content-Type: application/json)";
    if (const std::string* origin = req.header("origin");
        origin && *origin != "http://" + req.headerOr("host"))
        return "Origin '" + *origin + "' is not this server's page";
    if (!sameSecret(req.headerOr("x-cloudgraph-token"), mToken))
        return "a POST must carry this session's X-CloudGraph-Token (reload the page)";
    return "";
}

Response GraphServer::handle(const Request& req)
{
    if (const std::string why = refusal(req); !why.empty()) return errorReply(403, why);
    const auto route = mRoutes.find(req.path);
    if (route == mRoutes.end()) {
        if (req.path.rfind("/api/", 0) == 0) return errorReply(404, "no such route");
        if (req.method != "GET") return errorReply(405, "the page's files are read with GET");
        return staticFile(req);
    }
    const auto method = route->second.find(req.method);
    if (method == route->second.end())
        return errorReply(405, req.method + " is not allowed on " + req.path);
    try {
        return (this->*method->second)(req);
    } catch (const Refused& r) {
        return r.response;
    }
}

Response GraphServer::staticFile(const Request& req) const
{
    namespace fs = std::filesystem;
    const fs::path relative = fs::path(req.path == "/" ? "/index.html" : req.path).relative_path();
    for (const fs::path& part : relative)
        if (part.empty() || part.string().front() == '.')  // "..", ".", hidden files
            return errorReply(404, "not found");
    const fs::path file = mOptions.webDir / relative;
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (!fs::is_regular_file(file, ec) || ec || size > kMaxPageFileBytes)
        return errorReply(404, "not found");
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    Response res;
    res.contentType = contentType(file);
    res.body = text.str();
    if (file.extension() == ".html") {
        for (std::size_t at = res.body.find(kTokenPlaceholder); at != std::string::npos;
             at = res.body.find(kTokenPlaceholder, at))
            res.body.replace(at, kTokenPlaceholder.size(), mToken);
        res.headers.emplace_back("Cache-Control", "no-store");
    }
    return res;
}

Response GraphServer::edit(const std::function<void(GraphDocument&)>& change)
{
    try {
        std::lock_guard<std::mutex> lock(mDocMutex);
        change(*mDoc);
    } catch (const InputError& e) {
        return errorReply(400, e.what());
    }
    changed();
    return jsonReply(200, {{"version", mVersion.load()}});
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
                mBaseText = *text;
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

// The graph, the declarations of the node types it uses, and every type's name.
Response GraphServer::getGraph(const Request&)
{
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
    return jsonReply(200, {{"file", mOptions.graphFile.filename().string()},
                           {"graph", graph},
                           {"types", types},
                           {"registry", all},
                           {"version", mVersion.load()},
                           {"fileError", fileError}});
}

Response GraphServer::getVersion(const Request&)
{
    std::lock_guard<std::mutex> lock(mDocMutex);
    return jsonReply(200, {{"version", mVersion.load()}, {"fileError", mFileError}});
}

// The files an input-file parameter may name, relative to the graph.
Response GraphServer::getFiles(const Request&)
{
    return jsonReply(200, {{"files", filesBeside(mOptions.graphFile)}});
}

// Wiring edits (nodes added or deleted, inputs connected or not): the page sends the whole
// edited graph, loaded with the same type checks as a file.
Response GraphServer::postGraph(const Request& req)
{
    const nlohmann::json body = jsonBody(req, mOptions.load.maxJsonDepth);
    if (!body.contains("graph") || !body.at("graph").is_object())
        return errorReply(400, "'graph' must be a graph's JSON object");
    return edit([&](GraphDocument& doc) { doc.replace(body.at("graph").dump()); });
}

// One parameter, checked as `--set` and loading check it: 400 with the CLI's message.
Response GraphServer::postParam(const Request& req)
{
    const nlohmann::json body = jsonBody(req, mOptions.load.maxJsonDepth);
    const std::string node = stringField(body, "node");
    const std::string param = stringField(body, "param");
    if (!body.contains("value")) return errorReply(400, "'value' is missing");
    return edit([&](GraphDocument& doc) { doc.setParam(node, param, body.at("value")); });
}

// The document's complete graph, copied so that edits may go on while it cooks; or the 400
// reply saying what it lacks.
std::optional<Response> GraphServer::copyCompleteGraph(Graph& graph)
{
    try {
        std::lock_guard<std::mutex> lock(mDocMutex);
        graph = mDoc->completeGraph();
    } catch (const InputError& e) {
        return errorReply(400, e.what());
    }
    return std::nullopt;
}

// Cooks one output at a frame, with what it needs that the last cooks did not make.
Response GraphServer::postCook(const Request& req)
{
    const nlohmann::json body = jsonBody(req, mOptions.load.maxJsonDepth);
    const std::string node = stringField(body, "node");
    const std::string port = body.contains("port") ? stringField(body, "port") : "image";
    // With "write": true the writers below the node write this frame's files too.
    const bool write = boolField(body, "write", false);
    Graph graph;
    if (auto refused = copyCompleteGraph(graph)) return *refused;
    const int f = frameField(body, graph.frames);
    const auto started = std::chrono::steady_clock::now();
    DataPtr value;
    if (auto failed = cookFailure([&] {
            const bool writes = write && graph.find(node);
            value = mDoc->cook(graph, node, port, f, mOptions.cacheDir, mOptions.outDir,
                               writes ? writersBelow(graph, node) : std::vector<std::string>{});
        }))
        return *failed;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    nlohmann::json reply = {{"report", nlohmann::json::parse(mDoc->lastReport())},
                            {"seconds", seconds}};
    if (auto picture = previewPicture(value, previewDisplay(graph, node, port, f))) {
        std::string png = formats::encodePngRgb8(picture->width, picture->height, picture->rgb);
        std::lock_guard<std::mutex> lock(mPreviewMutex);
        mPreviews[node + "." + port] = std::move(png);
        std::string query;
        for (const auto& [name, text] : {std::pair{"node", node}, std::pair{"port", port}}) {
            query += query.empty() ? "?" : "&";
            query += std::string(name) + "=" + http::percentEncode(text);
        }
        reply["preview"] = "/api/preview" + query;
    }
    return jsonReply(200, reply);
}

// Where the cook under way stands: the page's progress bar polls it.
Response GraphServer::getProgress(const Request&)
{
    const CookProgress p = mDoc->progress();
    return jsonReply(200, {{"cooking", p.cooking},
                           {"done", p.done},
                           {"total", p.total},
                           {"seconds", p.seconds},
                           {"finished", p.finished}});
}

Response GraphServer::postCancel(const Request&)
{
    mDoc->cancel();
    return jsonReply(200, {{"ok", true}});
}

Response GraphServer::getPreview(const Request& req)
{
    const auto param = [&](const char* name, const char* fallback) {
        const auto it = req.query.find(name);
        return it == req.query.end() ? std::string(fallback) : it->second;
    };
    std::lock_guard<std::mutex> lock(mPreviewMutex);
    const auto it = mPreviews.find(param("node", "") + "." + param("port", "image"));
    if (it == mPreviews.end()) return errorReply(404, "no preview of that node yet");
    Response res;
    res.contentType = "image/png";
    res.body = it->second;
    res.headers.emplace_back("Cache-Control", "no-store");
    return res;
}

// The last frame at which the cloud `node` shows has particles (cli/LastCloudFrame.h), for
// the page to open on: {"frame": N}, or null when nothing upstream makes cloud particles or
// none has any. The samples are cooked as the page's cooks are (progress, cancel, cache).
Response GraphServer::getLastCloud(const Request& req)
{
    const auto it = req.query.find("node");
    if (it == req.query.end()) return errorReply(400, "'node' is missing");
    Graph graph;
    if (auto refused = copyCompleteGraph(graph)) return *refused;
    if (!graph.find(it->second)) return errorReply(400, "no node '" + it->second + "'");
    const auto source = cloudSourceOf(graph, it->second);
    if (!source) return jsonReply(200, {{"frame", nullptr}});
    const auto particlesAt = [&](int frame) -> std::size_t {
        const DataPtr value = mDoc->cook(graph, source->first, source->second, frame,
                                         mOptions.cacheDir, mOptions.outDir);
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(value);
        return cloud ? cloud->size() : 0;
    };
    std::optional<int> frame;
    if (auto failed = cookFailure([&] {
            frame =
                lastFrameWithParticles(particlesAt, graph.frames.start, graph.frames.end,
                                       std::max(1, (graph.frames.end - graph.frames.start) / 16));
        }))
        return *failed;
    return jsonReply(200, {{"frame", frame ? nlohmann::json(*frame) : nlohmann::json(nullptr)},
                           {"node", source->first}});
}

// Writes the edited graph back to its file, atomically; refuses (409) to replace a file that
// was changed outside the page since the page's graph was loaded or saved, unless the body
// says {"overwrite": true}.
Response GraphServer::postSave(const Request& req)
{
    const bool overwrite =
        req.body.empty() ? false
                         : boolField(jsonBody(req, mOptions.load.maxJsonDepth), "overwrite", false);
    std::optional<std::string> onDisk;
    try {
        onDisk = readGraphText(mOptions.graphFile, mOptions.load);
    } catch (const InputError&) {
        // gone or unreadable: a conflict too, since it is not what the page loaded
    }
    try {
        std::lock_guard<std::mutex> lock(mDocMutex);
        if (!overwrite && onDisk != mBaseText) {
            nlohmann::json reply = {
                {"error", mOptions.graphFile.string() +
                              (onDisk ? " was changed outside the page since it was loaded"
                                      : " is gone or unreadable") +
                              "; reload it, or overwrite it with the page's graph"},
                {"conflict", true}};
            return jsonReply(409, reply);
        }
        mFileText = mBaseText = mDoc->save(mOptions.graphFile);  // not a change from outside
        if (!mFileError.empty()) {  // an overwritten file that did not load now does
            mFileError.clear();
            changed();
        }
    } catch (const InputError& e) {
        return errorReply(400, e.what());
    }
    return jsonReply(200, {{"saved", mOptions.graphFile.string()}});
}

// A map painted on the page, for a ReadMap to read: {"node", "width", "height", "grey"} (hex,
// two digits a pixel, top row first) becomes a new file under --out/paintings named after
// the node whose map was painted; the reply gives its path. Writes nothing else.
Response GraphServer::postPaint(const Request& req)
{
    const nlohmann::json body = jsonBody(req, mOptions.load.maxJsonDepth);
    const std::string node = stringField(body, "node");
    const long width = integerField(body, "width");
    const long height = integerField(body, "height");
    const std::string grey = stringField(body, "grey");
    {
        std::lock_guard<std::mutex> lock(mDocMutex);
        if (!mDoc->graph().find(node)) return errorReply(400, "no node '" + node + "'");
    }
    try {
        const auto file = writePaintedMap(mOptions.outDir, node, width, height, grey);
        return jsonReply(200,
                         {{"file", std::filesystem::absolute(file).lexically_normal().string()}});
    } catch (const InputError& e) {
        return errorReply(400, std::string("painting: ") + e.what());
    }
}

}  // namespace cg::cli
