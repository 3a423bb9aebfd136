// `cloudgraph serve` end to end: the binary serving a small graph on a free port, driven
// over HTTP as the page drives it.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <set>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/ServeFixture.h"
#include "formats/PngFile.h"
#include "support/TestUtil.h"

namespace cg {
namespace {

using nlohmann::json;
using test::kServeGraph;
using test::ServeTest;

TEST_F(ServeTest, ServesTheGraphWithItsDeclarationsAndThePage)
{
    const auto page = client().Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("<title>CloudGraph</title>"), std::string::npos);

    const auto res = client().Get("/api/graph");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    const json reply = json::parse(res->body);
    EXPECT_EQ(reply["graph"]["nodes"].size(), 3u);
    EXPECT_EQ(reply["graph"]["nodes"]["render"]["params"]["width"], 64);
    EXPECT_EQ(reply["types"]["Renderer"]["outputs"][0]["type"], "Image");
    EXPECT_GT(reply["registry"].size(), 20u);
}

// The files an input-file parameter may name, offered by the page: those beside the graph,
// relative to it, hidden folders left out.
TEST_F(ServeTest, ListsTheFilesBesideTheGraph)
{
    for (const char* folder : {"soundings", ".git"})
        std::filesystem::create_directories(dir / folder);
    test::writeFile(dir / "soundings" / "day.txt", "x");
    test::writeFile(dir / ".git" / "config", "x");
    const json files = json::parse(client().Get("/api/files")->body)["files"];
    EXPECT_NE(std::find(files.begin(), files.end(), "graph.json"), files.end()) << files.dump();
    EXPECT_NE(std::find(files.begin(), files.end(), "soundings/day.txt"), files.end())
        << files.dump();
    for (const json& f : files) EXPECT_EQ(f.get<std::string>().find(".git"), std::string::npos);
}

TEST_F(ServeTest, RefusesAnOutOfRangeValueWithTheClisMessage)
{
    const auto res = post("/api/param", {{"node", "render"}, {"param", "width"}, {"value", 0}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
    const std::string error = json::parse(res->body)["error"];
    EXPECT_NE(error.find("/nodes/render/params/width"), std::string::npos) << error;
    EXPECT_NE(error.find("below the minimum 1"), std::string::npos) << error;
    // `run --set` gives the same words.
    const auto cli = test::runCli({"validate", graphFile().string(), "--set", "render.width=0"});
    EXPECT_EQ(cli.exitCode, 2);
    EXPECT_NE(cli.errors.find("below the minimum 1"), std::string::npos);
    // Nothing changed.
    const json graph = json::parse(client().Get("/api/graph")->body)["graph"];
    EXPECT_EQ(graph["nodes"]["render"]["params"]["width"], 64);
}

TEST_F(ServeTest, AnEditRecooksOnlyWhatItDirtiesAndChangesThePreview)
{
    const auto first = post("/api/cook", {{"node", "render"}, {"frame", 0}});
    ASSERT_TRUE(first);
    ASSERT_EQ(first->status, 200) << first->body;
    const std::string before = client().Get("/api/preview?node=render")->body;
    ASSERT_EQ(before.substr(1, 3), "PNG");

    ASSERT_EQ(post("/api/param",
                   {{"node", "render"}, {"param", "sunDirection"}, {"value", {-1.0, 0.5, 0.4}}})
                  ->status,
              200);
    const auto second = post("/api/cook", {{"node", "render"}, {"frame", 0}});
    ASSERT_EQ(second->status, 200) << second->body;
    std::map<std::string, std::string> status, reason;
    const json report = json::parse(second->body)["report"];
    for (const json& r : report["records"]) {
        const std::string node = r["node"].get<std::string>();
        status[node] = r["status"].get<std::string>();
        reason[node] = r.value("reason", "");
    }
    EXPECT_EQ(status["cloud"], "memory-hit");
    EXPECT_EQ(status["render"], "cooked");
    EXPECT_NE(reason["render"].find("sunDirection"), std::string::npos) << reason["render"];
    EXPECT_EQ(status.count("write"), 0u);  // downstream of the preview: not pulled
    EXPECT_NE(client().Get("/api/preview?node=render")->body, before);
}

// A long cook (the path tracer) reports its progress while it runs: the page's bar polls it.
TEST_F(ServeTest, ReportsTheProgressOfACookUnderWay)
{
    ASSERT_EQ(
        post("/api/param", {{"node", "render"}, {"param", "mode"}, {"value", "pathtrace"}})->status,
        200);
    ASSERT_EQ(
        post("/api/param", {{"node", "render"}, {"param", "samples"}, {"value", 512}})->status,
        200);
    std::thread cook([&] { post("/api/cook", {{"node", "render"}, {"frame", 0}}); });
    json during;
    for (int i = 0; i < 6000; ++i) {  // a minute at most (the sanitizer build is slow)
        during = json::parse(client().Get("/api/progress")->body);
        if (during["cooking"] == true && during["done"] == 1) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    cook.join();
    // The cumulus done, the Renderer not yet: one of the two node-frames.
    EXPECT_EQ(during["cooking"], true) << during.dump();
    EXPECT_EQ(during["done"], 1) << during.dump();
    EXPECT_EQ(during["total"], 2) << during.dump();
    EXPECT_EQ(during["finished"], json::array({"cloud"})) << during.dump();
    const json after = json::parse(client().Get("/api/progress")->body);
    EXPECT_EQ(after["cooking"], false);
    EXPECT_EQ(after["done"], 2);
    EXPECT_EQ(after["finished"], json::array({"cloud", "render"}));
    EXPECT_GT(after["seconds"].get<double>(), 0.0);
}

TEST_F(ServeTest, SavesTheEditAtomicallyAsAGraphTheCliLoads)
{
    ASSERT_EQ(post("/api/param", {{"node", "render"}, {"param", "fov"}, {"value", 55}})->status,
              200);
    const auto res = post("/api/save", json::object());
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    const json saved = test::readJson(graphFile());
    EXPECT_EQ(saved["nodes"]["render"]["params"]["fov"], 55.0);
    EXPECT_EQ(saved["nodes"]["render"]["params"]["width"], 64);
    EXPECT_EQ(test::runCli({"validate", graphFile().string()}).exitCode, 0);
    // In the file's own order (width, height, cameraPosition; not sorted), the new value
    // after them, the values not edited spelled as the file spelled them.
    const std::string text = test::readFile(graphFile());
    EXPECT_LT(text.find("\"width\""), text.find("\"height\""));
    EXPECT_LT(text.find("\"height\""), text.find("\"cameraPosition\""));
    EXPECT_LT(text.find("\"cameraPosition\""), text.find("\"fov\""));
    EXPECT_NE(text.find("\"voxelSize\": 40,"), std::string::npos) << text;
}

TEST_F(ServeTest, RefusesBadRequestsAndKeepsServing)
{
    // Outside the served folder, plain and percent-encoded.
    for (const char* path : {"/../CMakeLists.txt", "/%2e%2e/CMakeLists.txt", "/..%2fREADME.md"}) {
        const auto res = client().Get(path);
        ASSERT_TRUE(res) << path;
        EXPECT_GE(res->status, 400) << path;
        EXPECT_EQ(res->body.find("cmake_minimum_required"), std::string::npos) << path;
    }
    const auto malformed = postText("/api/param", "{\"node\": ", "application/json");
    ASSERT_TRUE(malformed);
    EXPECT_EQ(malformed->status, 400);
    const auto notObject = postText("/api/cook", "[1, 2]", "application/json");
    EXPECT_EQ(notObject->status, 400);
    const auto badFrame = post("/api/cook", {{"node", "render"}, {"frame", 99}});
    EXPECT_EQ(badFrame->status, 400);
    const auto unknownNode = post("/api/cook", {{"node", "nope"}, {"frame", 0}});
    EXPECT_EQ(unknownNode->status, 400);
    const std::string huge(8u << 20, 'x');
    const auto tooBig = postText("/api/param", huge, "application/json");
    ASSERT_TRUE(tooBig);
    EXPECT_EQ(tooBig->status, 413);
    EXPECT_EQ(client().Get("/api/graph")->status, 200);
}

// Another site's page open in the same browser may not drive the server: not by a form or
// fetch POST that is not JSON, not from another Origin, not through a DNS name of its own
// that resolves to 127.0.0.1. Nothing changes and nothing is saved.
TEST_F(ServeTest, RefusesRequestsFromOtherSites)
{
    const std::string edit = json{{"node", "render"}, {"param", "fov"}, {"value", 12}}.dump();
    const std::string ours = "127.0.0.1:" + std::to_string(port);
    const auto plain = postText("/api/param", edit, "text/plain");
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->status, 403);
    EXPECT_NE(plain->body.find("application/json"), std::string::npos) << plain->body;
    const auto foreign =
        postText("/api/param", edit, "application/json", {{"Origin", "http://evil.example"}});
    EXPECT_EQ(foreign->status, 403);
    const auto rebound =
        client().Get("/api/graph", {{"Host", "evil.example:" + std::to_string(port)}});
    EXPECT_EQ(rebound->status, 403);
    const auto save =
        postText("/api/save", "{}", "application/json", {{"Origin", "http://evil.example"}});
    EXPECT_EQ(save->status, 403);
    EXPECT_EQ(test::readFile(graphFile()), kServeGraph);  // not saved
    const json graph = json::parse(client().Get("/api/graph")->body)["graph"];
    EXPECT_FALSE(graph["nodes"]["render"]["params"].contains("fov"));  // not edited

    // The page itself: its own Origin, JSON.
    const auto own =
        postText("/api/param", edit, "application/json", {{"Origin", "http://" + ours}});
    EXPECT_EQ(own->status, 200) << own->body;
    EXPECT_EQ(client().Get("/api/graph", {{"Host", "localhost:" + std::to_string(port)}})->status,
              200);
}

TEST_F(ServeTest, AnswersConcurrentRequests)
{
    std::vector<std::thread> threads;
    std::vector<int> statuses(16, 0);
    for (int t = 0; t < 16; ++t)
        threads.emplace_back([&, t] {
            const auto res =
                t % 2
                    ? client().Get("/api/graph")
                    : post("/api/param", {{"node", "render"}, {"param", "fov"}, {"value", 30 + t}});
            statuses[static_cast<std::size_t>(t)] = res ? res->status : -1;
        });
    for (std::thread& t : threads) t.join();
    for (int s : statuses) EXPECT_EQ(s, 200);
}

TEST_F(ServeTest, WritesNothingButTheGraphAndUnderOut)
{
    ASSERT_EQ(post("/api/cook", {{"node", "write"}, {"port", "files"}, {"frame", 1}})->status, 200);
    ASSERT_EQ(post("/api/save", json::object())->status, 200);
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path()))
        if (e.is_regular_file() && e.path().string().rfind((dir / "cache").string(), 0) != 0)
            files.push_back(std::filesystem::relative(e.path(), dir.path()).string());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"graph.json", "out/still.0001.png"}));
}

TEST_F(ServeTest, WritesTheFramesOfTheWritersBelowWhenAsked)
{
    // The preview shows the image as the WriteImage below writes it: its exposure, tone
    // curve and dither (seeded by the frame), so the two are the same pixels.
    ASSERT_EQ(
        post("/api/param", {{"node", "write"}, {"param", "exposure"}, {"value", 1.5}})->status,
        200);
    ASSERT_EQ(
        post("/api/param", {{"node", "write"}, {"param", "toneMap"}, {"value", "hable"}})->status,
        200);
    const json cook = {{"node", "render"}, {"frame", 1}, {"write", true}};
    const auto first = post("/api/cook", cook);
    ASSERT_TRUE(first);
    ASSERT_EQ(first->status, 200) << first->body;
    ASSERT_TRUE(std::filesystem::exists(dir / "out" / "still.0001.png"));
    test::writeFile(dir / "preview.png", client().Get("/api/preview?node=render")->body);
    EXPECT_EQ(formats::readPngRgb8((dir / "preview.png").string()).rgb,
              formats::readPngRgb8((dir / "out" / "still.0001.png").string()).rgb);
    std::filesystem::remove(dir / "preview.png");
    // Again: the writer's file still verifies, so it is skipped with the render only it
    // read; the preview is still the Renderer's (from the cache).
    const auto again = post("/api/cook", cook);
    ASSERT_TRUE(again) << "the server went away";
    ASSERT_EQ(again->status, 200) << again->body;
    EXPECT_EQ(json::parse(again->body)["preview"], "/api/preview?node=render&port=image");
    EXPECT_EQ(post("/api/cook", {{"node", "render"}, {"frame", 1}, {"write", "yes"}})->status, 400);
}

TEST_F(ServeTest, WiringEditsAreCheckedAsLoadingChecksThem)
{
    json graph = json::parse(client().Get("/api/graph")->body)["graph"];
    // A FogVolume output into an Image input: refused with the loader's words.
    json wrong = graph;
    wrong["nodes"]["write"]["inputs"]["image"] = "cloud.volume";
    const auto refused = post("/api/graph", {{"graph", wrong}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
    const std::string error = json::parse(refused->body)["error"];
    EXPECT_NE(error.find("/nodes/write/inputs/image"), std::string::npos) << error;
    EXPECT_EQ(json::parse(client().Get("/api/graph")->body)["graph"], graph);  // unchanged

    // Add a second renderer wired to the cumulus, cook it, then delete it again.
    json added = graph;
    added["nodes"]["render2"] = {{"type", "Renderer"},
                                 {"inputs", {{"volume", "cloud.volume"}}},
                                 {"params", {{"width", 32}, {"height", 24}}}};
    ASSERT_EQ(post("/api/graph", {{"graph", added}})->status, 200);
    const auto cooked = post("/api/cook", {{"node", "render2"}, {"frame", 0}});
    ASSERT_EQ(cooked->status, 200) << cooked->body;
    // Disconnected, the renderer is kept but cannot cook: the CLI's refusal of the graph.
    added["nodes"]["render2"].erase("inputs");
    ASSERT_EQ(post("/api/graph", {{"graph", added}})->status, 200);
    const auto incomplete = post("/api/cook", {{"node", "render"}, {"frame", 0}});
    EXPECT_EQ(incomplete->status, 400);
    EXPECT_NE(json::parse(incomplete->body)["error"].get<std::string>().find("render2"),
              std::string::npos);
    ASSERT_EQ(post("/api/graph", {{"graph", graph}})->status, 200);
    EXPECT_EQ(post("/api/cook", {{"node", "render"}, {"frame", 0}})->status, 200);
}

TEST_F(ServeTest, ReloadsTheGraphWhenItsFileChangesOnDisk)
{
    const int version = json::parse(client().Get("/api/version")->body)["version"];
    json edited = test::readJson(graphFile());
    edited["nodes"]["render"]["params"]["fov"] = 33;
    editFile(edited.dump(2));
    json reply;
    for (int i = 0; i < 100; ++i) {
        reply = json::parse(client().Get("/api/version")->body);
        if (reply["version"] != version) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_NE(reply["version"], version) << "the change on disk was not seen";
    EXPECT_EQ(reply["fileError"], "");
    const json graph = json::parse(client().Get("/api/graph")->body)["graph"];
    EXPECT_EQ(graph["nodes"]["render"]["params"]["fov"], 33.0);

    // A file that does not load is reported; the graph stays as it was.
    editFile(R"({"cloudgraph": 1, "nodes": {"x": {"type": "Nope"}}})");
    for (int i = 0; i < 100; ++i) {
        reply = json::parse(client().Get("/api/version")->body);
        if (reply["fileError"] != "") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_NE(reply["fileError"].get<std::string>().find("Nope"), std::string::npos)
        << reply.dump();
    EXPECT_EQ(json::parse(client().Get("/api/graph")->body)["graph"], graph);

    // Nor is a file over the loader's size limit read at all.
    editFile(std::string((64u << 20) + 1, ' '));
    for (int i = 0; i < 100; ++i) {
        reply = json::parse(client().Get("/api/version")->body);
        if (reply["fileError"].get<std::string>().find("over the limit") != std::string::npos)
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_NE(reply["fileError"].get<std::string>().find("over the limit"), std::string::npos)
        << reply.dump();
    EXPECT_EQ(json::parse(client().Get("/api/graph")->body)["graph"], graph);

    // A good file again: loaded, the error gone.
    edited["nodes"]["render"]["params"]["fov"] = 34;
    editFile(edited.dump(2));
    for (int i = 0; i < 100; ++i) {
        reply = json::parse(client().Get("/api/version")->body);
        if (reply["fileError"] == "") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_EQ(reply["fileError"], "");
    EXPECT_EQ(
        json::parse(client().Get("/api/graph")->body)["graph"]["nodes"]["render"]["params"]["fov"],
        34.0);
}

/// A density map and the vapour emitted over it, for the previews of what is not an image.
const char* kMapGraph = R"({
  "cloudgraph": 1,
  "frames": {"start": 0, "end": 0},
  "nodes": {
    "noise": {"type": "NoiseMap", "params": {"width": 32, "height": 16, "seed": 3}},
    "emit": {"type": "VapourEmitter", "inputs": {"map": "noise.map"},
             "params": {"maxHeight": 800}}
  }
})";

class ServePreviewTest : public ServeTest {
protected:
    const char* graphText() const override { return kMapGraph; }
    /// The preview of output `output` of `node` at frame 0, decoded.
    formats::Rgb8Image preview(const std::string& node, const std::string& output)
    {
        const auto cooked = post("/api/cook", {{"node", node}, {"port", output}, {"frame", 0}});
        EXPECT_EQ(cooked->status, 200) << cooked->body;
        const std::string url = json::parse(cooked->body)["preview"];
        EXPECT_EQ(url, "/api/preview?node=" + node + "&port=" + output);
        test::writeFile(dir / "preview.png", client().Get(url.c_str())->body);
        return formats::readPngRgb8((dir / "preview.png").string());
    }
};

// A map: one grey pixel a cell (north up), from black to white over the map's range.
TEST_F(ServePreviewTest, ShowsAMapAsGreyCells)
{
    const formats::Rgb8Image map = preview("noise", "map");
    ASSERT_EQ(map.width, 32);
    ASSERT_EQ(map.height, 16);
    std::set<int> greys;
    for (std::size_t i = 0; i < map.rgb.size(); i += 3) {
        EXPECT_EQ(map.rgb[i], map.rgb[i + 1]);
        EXPECT_EQ(map.rgb[i], map.rgb[i + 2]);
        greys.insert(map.rgb[i]);
    }
    EXPECT_GT(greys.size(), 20u);  // a noise map, not a flat one
}

// Particles: points seen from the side, over a dark ground, in a picture 640 wide whose
// height follows their extent (the emitter's 0-800 m over a 32-cell map).
TEST_F(ServePreviewTest, ShowsParticlesAsPoints)
{
    const formats::Rgb8Image points = preview("emit", "particles");
    ASSERT_EQ(points.width, 640);
    EXPECT_GE(points.height, 64);
    std::size_t lit = 0;
    for (std::size_t i = 0; i < points.rgb.size(); i += 3) lit += points.rgb[i] > 100;
    EXPECT_GT(lit, 20u);
    EXPECT_LT(lit, points.rgb.size() / 3 / 2);  // points, not a wash
}

/// `grey` as the page sends a painting: two hex digits a pixel.
std::string hexOf(const std::vector<std::uint8_t>& grey)
{
    std::string hex;
    for (const std::uint8_t g : grey) {
        constexpr const char* kDigits = "0123456789abcdef";
        hex += kDigits[g >> 4];
        hex += kDigits[g & 15];
    }
    return hex;
}

// A painting on the map's preview becomes a new PNG under out/paintings that a ReadMap reads
// back as the painted cells, bit for bit in the preview; a second never replaces the first;
// a bad one is refused naming what is wrong, and writes nothing.
TEST_F(ServePreviewTest, APaintingIsANewPngThatReadMapReadsAsPainted)
{
    const formats::Rgb8Image map = preview("noise", "map");
    std::vector<std::uint8_t> grey(static_cast<std::size_t>(map.width) * map.height);
    for (std::size_t i = 0; i < grey.size(); ++i) grey[i] = map.rgb[3 * i];
    for (int y = 2; y < 6; ++y)
        for (int x = 20; x < 28; ++x) grey[static_cast<std::size_t>(y) * map.width + x] = 255;
    const json painting = {
        {"node", "noise"}, {"width", map.width}, {"height", map.height}, {"grey", hexOf(grey)}};
    const auto first = post("/api/paint", painting);
    ASSERT_EQ(first->status, 200) << first->body;
    const std::filesystem::path file = json::parse(first->body)["file"].get<std::string>();
    EXPECT_EQ(file, std::filesystem::absolute(dir / "out" / "paintings" / "noise.1.png"));
    const std::string firstBytes = test::readFile(file);
    const auto second = post("/api/paint", painting);
    ASSERT_EQ(second->status, 200) << second->body;
    EXPECT_EQ(
        std::filesystem::path(json::parse(second->body)["file"].get<std::string>()).filename(),
        "noise.2.png");
    EXPECT_EQ(test::readFile(file), firstBytes);

    json graph = json::parse(client().Get("/api/graph")->body)["graph"];
    graph["nodes"]["painted"] = {{"type", "ReadMap"}, {"params", {{"file", file.string()}}}};
    ASSERT_EQ(post("/api/graph", {{"graph", graph}})->status, 200);
    const formats::Rgb8Image back = preview("painted", "map");
    ASSERT_EQ(back.width, map.width);
    ASSERT_EQ(back.height, map.height);
    for (std::size_t i = 0; i < grey.size(); ++i) ASSERT_EQ(back.rgb[3 * i], grey[i]) << i;

    json shortGrey = painting, notHex = painting, huge = painting, nobody = painting;
    shortGrey["grey"] = hexOf(std::vector<std::uint8_t>(10));
    notHex["grey"] = std::string(2 * grey.size(), 'g');
    huge["width"] = 100000;
    huge["height"] = 100000;
    nobody["node"] = "nobody";
    for (const auto& [bad, says] :
         std::vector<std::pair<json, std::string>>{{shortGrey, "two a pixel"},
                                                   {notHex, "not a hexadecimal digit"},
                                                   {huge, "at most 500000 pixels"},
                                                   {nobody, "no node 'nobody'"}}) {
        const auto reply = post("/api/paint", bad);
        EXPECT_EQ(reply->status, 400);
        EXPECT_NE(reply->body.find(says), std::string::npos) << reply->body;
    }
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir / "out" / "paintings"))
        files += e.is_regular_file();
    EXPECT_EQ(files, 2u);
}

// Where the page opens: the last frame with cloud particles upstream of the preview; this
// graph's cloud is a synthetic volume, with no particles, so the page stays where it is.
TEST_F(ServeTest, TheLastCloudFrameIsNullWithoutCloudParticlesAndANodeIsRequired)
{
    const auto res = client().Get("/api/lastcloud?node=render");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    EXPECT_TRUE(json::parse(res->body)["frame"].is_null());
    const auto missing = client().Get("/api/lastcloud");
    ASSERT_TRUE(missing);
    EXPECT_EQ(missing->status, 400);
    const auto unknown = client().Get("/api/lastcloud?node=nothing");
    ASSERT_TRUE(unknown);
    EXPECT_EQ(unknown->status, 400);
    EXPECT_NE(unknown->body.find("nothing"), std::string::npos);
}

TEST_F(ServeTest, StopsOnSigterm)
{
    server->kill(SIGTERM);
    EXPECT_EQ(server->wait().exitCode, 0);
}

}  // namespace
}  // namespace cg
