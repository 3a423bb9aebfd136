// The fast renderer's error against the reference path tracer: for each volume and each sun
// (in front of the camera, beside it, behind it; 35° above the horizon), renders both,
// prints the luminance error over the cloud's pixels as a markdown table, and writes the two
// pictures side by side. bench/run_render_reference.sh runs it on the synthetic cumulus, a
// frame of Figure 6 and a frame of Figure 9.
//
// Usage: render_error [options] CASE...
//   CASE: synthetic, or NAME=FILE.vdb@EXTINCTION@CX,CY,CZ@LX,LY,LZ@FOV (camera position,
//         look-at point, vertical field of view in degrees; grid "density")
//   --samples N    reference paths a pixel (default 256)
//   --size WxH     image size (default 240x180)
//   --png DIR      write DIR/NAME_SUN.png: fast | reference, tone-mapped as WriteImage does
//   --fast K=V     a fast-mode setting: lightTexel, step, cellVoxels, or octaves=N for the
//                  octave model instead of the diffusion solve (to explore, to compare)
//   --cache DIR    keep reference images there and reuse them (they depend only on the
//                  case, the sun, the size and the sample count)
//
// Cloud pixels are those whose reference opacity is at least 0.5; the error of a pixel is
// |L_fast − L_ref| / L_ref of its luminance (beauty, background included).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "algo/render/Display.h"
#include "algo/render/RenderPathTrace.h"
#include "algo/render/RenderVolume.h"
#include "algo/render/SyntheticCumulus.h"
#include "formats/PngFile.h"

namespace {

using cg::algo::RenderVec3;

struct Case {
    std::string name;
    openvdb::FloatGrid::Ptr grid;
    cg::algo::RenderSettings settings;
};

RenderVec3 parseVec3(const std::string& text)
{
    double v[3] = {0, 0, 0};
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf", &v[0], &v[1], &v[2]) != 3)
        throw std::runtime_error("not x,y,z: " + text);
    return {v[0], v[1], v[2]};
}

std::vector<std::string> split(const std::string& text, char sep)
{
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, sep);) out.push_back(part);
    return out;
}

/// graphs/cumulus_still.json's cloud and camera.
Case syntheticCase()
{
    cg::algo::SyntheticCumulusSettings c;
    c.seed = 3;
    c.voxelSize = 10.0;
    c.baseHeight = 900.0;
    c.baseRadius = 700.0;
    c.towerHeight = 1.3;
    Case out;
    out.name = "synthetic";
    out.grid = cg::algo::rasterizeCumulus(cg::algo::cumulusBlobs(c), c);
    out.settings.camera.position = RenderVec3(400, -3800, 700);
    out.settings.camera.lookAt = RenderVec3(0, 0, 1200);
    out.settings.camera.fovDegrees = 40.0;
    out.settings.medium.extinction = 0.05;
    return out;
}

Case fileCase(const std::string& spec)
{
    const auto eq = spec.find('=');
    if (eq == std::string::npos) throw std::runtime_error("bad case: " + spec);
    const std::vector<std::string> f = split(spec.substr(eq + 1), '@');
    if (f.size() != 5) throw std::runtime_error("bad case: " + spec);
    Case out;
    out.name = spec.substr(0, eq);
    openvdb::io::File file(f[0]);
    file.open();
    out.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    file.close();
    if (!out.grid) throw std::runtime_error(f[0] + ": 'density' is not a float grid");
    out.settings.medium.extinction = std::stod(f[1]);
    out.settings.camera.position = parseVec3(f[2]);
    out.settings.camera.lookAt = parseVec3(f[3]);
    out.settings.camera.fovDegrees = std::stod(f[4]);
    return out;
}

/// Toward a sun 35° above the horizon, in front of the camera (the camera looks toward
/// it), beside it (from the camera's right) or behind it.
RenderVec3 sunToward(const cg::algo::RenderCamera& camera, const std::string& where)
{
    RenderVec3 f = camera.lookAt - camera.position;
    f = RenderVec3(f.x(), f.y(), 0.0).unitSafe();
    const RenderVec3 right(f.y(), -f.x(), 0.0);
    const RenderVec3 h = where == "front" ? f : where == "behind" ? -f : right;
    const double e = 35.0 * M_PI / 180.0;
    return h * std::cos(e) + RenderVec3(0, 0, std::sin(e));
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

struct Errors {
    std::size_t pixels = 0;
    double ratio = 0.0;      ///< mean L_fast / mean L_ref over cloud pixels
    double mean = 0.0;       ///< mean relative error
    double p90 = 0.0;        ///< its 90th percentile
    double darkMean = 0.0;   ///< mean relative error over the darker half (by reference)
    double brightMean = 0.0; ///< over the brighter half
};

Errors compare(const cg::algo::RenderedImage& fast, const cg::algo::RenderedImage& ref)
{
    std::vector<std::pair<double, double>> refAndErr;  // (L_ref, relative error)
    double sumFast = 0.0, sumRef = 0.0;
    for (std::size_t i = 0; i < ref.rgba.size() / 4; ++i) {
        if (ref.rgba[4 * i + 3] < 0.5f) continue;
        const double lr = luminance(&ref.rgba[4 * i]), lf = luminance(&fast.rgba[4 * i]);
        if (!(lr > 0.0)) continue;
        refAndErr.emplace_back(lr, std::abs(lf - lr) / lr);
        sumFast += lf;
        sumRef += lr;
    }
    Errors e;
    e.pixels = refAndErr.size();
    if (e.pixels == 0) return e;
    e.ratio = sumFast / sumRef;
    std::vector<double> errs;
    for (const auto& [l, err] : refAndErr) errs.push_back(err);
    for (const double v : errs) e.mean += v / errs.size();
    std::vector<double> sorted = errs;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() * 9 / 10, sorted.end());
    e.p90 = sorted[sorted.size() * 9 / 10];
    std::sort(refAndErr.begin(), refAndErr.end());
    const std::size_t half = refAndErr.size() / 2;
    for (std::size_t i = 0; i < refAndErr.size(); ++i)
        (i < half ? e.darkMean : e.brightMean) += refAndErr[i].second;
    e.darkMean /= std::max<std::size_t>(half, 1);
    e.brightMean /= std::max<std::size_t>(refAndErr.size() - half, 1);
    return e;
}

bool readCached(const std::filesystem::path& path, cg::algo::RenderedImage& img)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    in.read(reinterpret_cast<char*>(img.rgba.data()),
            static_cast<std::streamsize>(img.rgba.size() * sizeof(float)));
    return static_cast<bool>(in);
}

void writeCached(const std::filesystem::path& path, const cg::algo::RenderedImage& img)
{
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(img.rgba.data()),
              static_cast<std::streamsize>(img.rgba.size() * sizeof(float)));
}

void writeSideBySide(const std::string& path, const cg::algo::RenderedImage& a,
                     const cg::algo::RenderedImage& b)
{
    cg::algo::DisplaySettings display;
    const auto ra = cg::algo::displayRgb8(a.rgba, a.width, a.height, display);
    const auto rb = cg::algo::displayRgb8(b.rgba, b.width, b.height, display);
    const int w = a.width, h = a.height, gap = 4;
    std::vector<std::uint8_t> out(static_cast<std::size_t>(2 * w + gap) * h * 3, 255);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const std::size_t src = (static_cast<std::size_t>(y) * w + x) * 3 + c;
                out[(static_cast<std::size_t>(y) * (2 * w + gap) + x) * 3 + c] = ra[src];
                out[(static_cast<std::size_t>(y) * (2 * w + gap) + w + gap + x) * 3 + c] = rb[src];
            }
    cg::formats::writePngRgb8(path, 2 * w + gap, h, out);
}

double seconds(std::chrono::steady_clock::time_point since)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    int samples = 256, width = 240, height = 180;
    std::string pngDir, cacheDir;
    std::vector<Case> cases;
    std::vector<std::pair<std::string, double>> fastSettings;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            const auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
                return argv[++i];
            };
            if (arg == "--samples") samples = std::stoi(value());
            else if (arg == "--size") {
                if (std::sscanf(value().c_str(), "%dx%d", &width, &height) != 2)
                    throw std::runtime_error("--size WxH");
            } else if (arg == "--png") pngDir = value();
            else if (arg == "--cache") cacheDir = value();
            else if (arg == "--fast") {
                const std::string kv = value();
                const auto eq = kv.find('=');
                if (eq == std::string::npos) throw std::runtime_error("--fast K=V");
                fastSettings.emplace_back(kv.substr(0, eq), std::stod(kv.substr(eq + 1)));
            }
            else if (arg == "synthetic") cases.push_back(syntheticCase());
            else cases.push_back(fileCase(arg));
        }
        if (cases.empty()) throw std::runtime_error("no case given");
    } catch (const std::exception& e) {
        std::cerr << "render_error: " << e.what() << "\n";
        return 2;
    }

    std::printf("| volume | sun | cloud px | fast / ref | mean error | 90th pct | darker half | "
                "brighter half | fast | reference |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (Case& c : cases) {
        for (const std::string where : {"front", "beside", "behind"}) {
            cg::algo::RenderSettings s = c.settings;
            s.camera.width = width;
            s.camera.height = height;
            s.sun.direction = sunToward(s.camera, where);
            s.pathTrace.samples = samples;
            cg::algo::RenderSettings fastS = s;
            for (const auto& [key, v] : fastSettings) {
                if (key == "lightTexel") fastS.march.lightTexel = v;
                else if (key == "step") fastS.march.step = v;
                else if (key == "cellVoxels") fastS.multiScatter.cellVoxels = static_cast<int>(v);
                else if (key == "octaves") {  // the model before the diffusion solve
                    fastS.multiScatter.model = cg::algo::MultiScatterModel::Octaves;
                    fastS.multiScatter.octaves = static_cast<int>(v);
                }
                else throw std::runtime_error("unknown fast setting " + key);
            }

            auto start = std::chrono::steady_clock::now();
            const cg::algo::RenderedImage fast = cg::algo::renderFogVolume(*c.grid, fastS);
            const double fastSeconds = seconds(start);

            cg::algo::RenderedImage ref;
            ref.width = width;
            ref.height = height;
            ref.rgba.resize(fast.rgba.size());
            const std::filesystem::path cached =
                cacheDir.empty() ? std::filesystem::path()
                                 : std::filesystem::path(cacheDir) /
                                       (c.name + "_" + where + "_" + std::to_string(width) + "x" +
                                        std::to_string(height) + "_" + std::to_string(samples) +
                                        ".f32");
            double refSeconds = 0.0;
            if (cached.empty() || !readCached(cached, ref)) {
                start = std::chrono::steady_clock::now();
                ref = cg::algo::renderPathTraced(*c.grid, s);
                refSeconds = seconds(start);
                if (!cached.empty()) {
                    std::filesystem::create_directories(cacheDir);
                    writeCached(cached, ref);
                }
            }
            const Errors e = compare(fast, ref);
            std::printf("| %s | %s | %zu | %.2f | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.3f s | %s |\n",
                        c.name.c_str(), where.c_str(), e.pixels, e.ratio, 100 * e.mean,
                        100 * e.p90, 100 * e.darkMean, 100 * e.brightMean, fastSeconds,
                        refSeconds > 0.0 ? (std::to_string(refSeconds) + " s").c_str()
                                         : "cached");
            std::fflush(stdout);
            if (!pngDir.empty()) {
                std::filesystem::create_directories(pngDir);
                writeSideBySide(pngDir + "/" + c.name + "_" + where + ".png", fast, ref);
            }
        }
    }
    return 0;
}
