#pragma once
/// The HTTP side of `cloudgraph serve`: the page's files and a small JSON API over one
/// GraphDocument (docs/serve.md lists the routes). Edits are checked exactly as the CLI
/// checks a graph; a cook recooks only what an edit dirtied, since the document keeps its
/// evaluator (and the --cache) between cooks. Nothing is written but the graph file (on
/// save), what writers write under --out and the maps painted on the page (new files under
/// --out/paintings). docs/reliability.md states whom it trusts.

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cli/http/HttpServer.h"
#include "core/GraphDocument.h"
#include "core/Registry.h"

namespace cg::cli {

struct ServeOptions {
    std::filesystem::path graphFile;
    std::filesystem::path webDir;  ///< the page's files, served read-only
    std::string outDir = "out";
    std::string cacheDir;  ///< empty: memory only
    std::string host = "127.0.0.1";
    /// Further names the Host header may give (a LAN name when --host is 0.0.0.0), as
    /// "name" or "name:port"; the server's own loopback names and --host are always allowed.
    std::vector<std::string> allowedHosts;
    int port = 8642;  ///< 0: any free port
    LoadOptions load;
    std::vector<std::string> sets;  ///< --set node.param=value, applied after loading
};

class GraphServer {
public:
    /// Loads the graph (InputError when it is bad: nothing is served).
    GraphServer(const Registry& registry, ServeOptions options);
    ~GraphServer();

    /// Binds the socket; returns the port (the one chosen when options.port is 0). Throws
    /// InputError naming --port or --host when it cannot.
    int bind();
    /// Serves until stop().
    void listen();
    /// Cancels a cook under way and makes listen() return (also when called before it).
    void stop();

    /// Answers one request as the server does, without a socket (tests and the fuzzer).
    http::Response handle(const http::Request& req);
    /// The secret the page sends with every POST (X-CloudGraph-Token), so that a page of
    /// another origin, which cannot read ours, cannot make one.
    const std::string& token() const { return mToken; }

private:
    using Route = http::Response (GraphServer::*)(const http::Request&);

    /// Why `req` may not be answered, or "" when it may.
    std::string refusal(const http::Request& req) const;
    http::Response staticFile(const http::Request& req) const;
    http::Response getGraph(const http::Request& req);
    http::Response getVersion(const http::Request& req);
    http::Response getFiles(const http::Request& req);
    http::Response postGraph(const http::Request& req);
    http::Response postParam(const http::Request& req);
    http::Response postCook(const http::Request& req);
    http::Response getProgress(const http::Request& req);
    http::Response postCancel(const http::Request& req);
    http::Response getPreview(const http::Request& req);
    http::Response getLastCloud(const http::Request& req);
    std::optional<http::Response> copyCompleteGraph(Graph& graph);
    http::Response postSave(const http::Request& req);
    http::Response postPaint(const http::Request& req);

    /// Until stop(): reloads the graph when its file changes on disk (a text editor's save),
    /// through the same checks; a file that does not load is reported and the graph kept.
    void watchFile();
    /// Marks the graph changed, for pages polling /api/version.
    void changed() { ++mVersion; }
    /// Applies `change` to the document: the new version, or 400 with the loader's message
    /// and the graph as it was.
    http::Response edit(const std::function<void(GraphDocument&)>& change);

    ServeOptions mOptions;
    const Registry& mRegistry;
    const std::string mToken;
    std::map<std::string, std::map<std::string, Route>> mRoutes;  ///< path -> method -> route
    http::Server mServer;
    std::atomic<int> mPort{0};  ///< the port it listens on, once bound
    std::mutex mDocMutex;       ///< guards mDoc's graph (edits, snapshots, save)
    std::unique_ptr<GraphDocument> mDoc;
    std::mutex mPreviewMutex;
    std::map<std::string, std::string> mPreviews;  ///< "node.port": PNG of its last cook

    std::atomic<int> mVersion{1};  ///< of the graph: every edit, reload and save adds one
    std::string mFileText;         ///< the file as last seen by the watcher or saved (mDocMutex)
    /// The file the document was last loaded from or saved to (under mDocMutex): Save
    /// refuses to replace a file that differs from it, as an edit made outside the page.
    std::string mBaseText;
    std::string mFileError;  ///< why the file on disk did not load (under mDocMutex)
    std::mutex mStopMutex;
    std::condition_variable mStopped;
    bool mStopping = false;
};

}  // namespace cg::cli
