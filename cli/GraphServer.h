#pragma once
/// The HTTP side of `cloudgraph serve`: the page's files and a small JSON API over one
/// GraphDocument (docs/serve.md lists the routes). Edits are checked exactly as the CLI
/// checks a graph; a cook recooks only what an edit dirtied, since the document keeps its
/// evaluator (and the --cache) between cooks. Nothing is written but the graph file (on
/// save) and what writers write under --out.

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/GraphDocument.h"
#include "core/Registry.h"

namespace httplib {
class Server;
struct Response;
}

namespace cg::cli {

struct ServeOptions {
    std::filesystem::path graphFile;
    std::filesystem::path webDir;  ///< the page's files, served read-only
    std::string outDir = "out";
    std::string cacheDir;          ///< empty: memory only
    std::string host = "127.0.0.1";
    int port = 8642;               ///< 0: any free port
    LoadOptions load;
    std::vector<std::string> sets;  ///< --set node.param=value, applied after loading
};

class GraphServer {
public:
    /// Loads the graph (InputError when it is bad: nothing is served).
    GraphServer(const Registry& registry, ServeOptions options);
    ~GraphServer();

    /// Binds the socket; returns the port (the one chosen when options.port is 0). Throws
    /// InputError naming --port when it cannot.
    int bind();
    /// Serves until stop().
    void listen();
    /// Cancels a cook under way and makes listen() return (waiting, if listen() has not
    /// begun yet, until it has: call it only once listen() is called or about to be).
    void stop();

private:
    void routes();
    /// Until stop(): reloads the graph when its file changes on disk (a text editor's save),
    /// through the same checks; a file that does not load is reported and the graph kept.
    void watchFile();
    /// Marks the graph changed, for pages polling /api/version.
    void changed() { ++mVersion; }
    /// Applies `change` to the document: the new version, or 400 with the loader's message
    /// and the graph as it was.
    void edit(httplib::Response& res, const std::function<void(GraphDocument&)>& change);

    ServeOptions mOptions;
    const Registry& mRegistry;
    std::unique_ptr<httplib::Server> mServer;
    int mListenSocket = -1;  ///< the server's listening socket, once bound
    std::atomic<int> mPort{0};  ///< the port it listens on, once bound
    std::atomic<bool> mListenEnded{false};  ///< listen() has returned
    std::mutex mDocMutex;  ///< guards mDoc's graph (edits, snapshots, save)
    std::unique_ptr<GraphDocument> mDoc;
    std::mutex mPreviewMutex;
    std::map<std::string, std::string> mPreviews;  ///< "node.port": PNG of its last cook

    std::atomic<int> mVersion{1};  ///< of the graph: every edit, reload and save adds one
    std::string mFileText;         ///< the file as last loaded or saved (under mDocMutex)
    std::string mFileError;        ///< why the file on disk did not load (under mDocMutex)
    std::mutex mStopMutex;
    std::condition_variable mStopped;
    bool mStopping = false;
};

}  // namespace cg::cli
