// The fast renderer's error against the reference path tracer: for each volume and each sun
// (in front of the camera, beside it, behind it; 35° above the horizon), renders both,
// prints the luminance error over the cloud's pixels as a markdown table, and writes the two
// pictures side by side. bench/run_render_reference.sh runs it on the synthetic cumulus, a
// frame of Figure 6 and a frame of Figure 9.
//
// Usage: render_error [options] CASE...
//   CASE: synthetic, box (a homogeneous cube), or NAME=FILE.vdb@EXTINCTION@CX,CY,CZ@LX,LY,LZ@FOV
//   (camera position,
//         look-at point, vertical field of view in degrees; grid "density")
//   --samples N    reference paths a pixel, both halves together (default 256)
//   --size WxH     image size (default 240x180)
//   --png DIR      write DIR/NAME_SUN.png: fast | reference, tone-mapped as WriteImage does
//   --fast K=V     a fast-mode setting: lightTexel, step, coarseTransmittance, cellVoxels,
//                  or octaves=N for the octave model instead of the diffusion solve (to
//                  explore, to compare)
//   --scene K=V    a scene setting for both renderers: ambient (sky light scale), sun
//                  (intensity), skyRadiance (scales the sky's colours, 0 = a black sky, so
//                  a camera in the clear air sees only what the clouds send it), haze (the
//                  ground's haze distance, m, 0 = none), ground (0 or 1), groundAlbedo
//                  (grey), albedo (the cloud's single-scattering albedo), bounces (the reference's
//                  maxBounces; with --fast octaves=1, single scattering alone), to take the light
//                  apart; mie=D, the Mie phase function of droplets D μm across
//   --cache DIR    keep reference images there and reuse them; a file's name holds what the
//                  image depends on: the case's name and a hash (core/Hash.h) of its grid's
//                  voxels, transform, camera and extinction, the sun, the size, the scene
//                  settings, the sample count and the seed (so an edited .vdb under the same
//                  name is rendered again, not read back stale)
//   --seed N       the reference's random seeds are 2N and 2N + 1 (default N = 0)
//
// The reference is the mean of two halves of samples/2 paths each with independent seeds;
// the "reference noise" column is their disagreement, the scale of the reference's own
// error: a fast-mode error near it is not measured, only bounded.
//
// Cloud pixels are those whose reference opacity is at least 0.5; the error of a pixel is
// |L_fast − L_ref| / L_ref of its luminance (beauty, background included).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
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

#include "algo/render/image/Display.h"
#include "algo/render/integrators/RenderPathTrace.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/metrics/RenderError.h"
#include "core/Hash.h"
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
    cg::algo::ErrorScene scene = cg::algo::stillCumulusScene(10.0);
    return {"synthetic", scene.grid, scene.settings};
}

/// A homogeneous cube, 1 km wide, 500 m above the ground: the simplest thick cloud.
Case boxCase()
{
    Case out;
    out.name = "box";
    out.grid = openvdb::FloatGrid::create(0.0f);
    out.grid->setTransform(openvdb::math::Transform::createLinearTransform(20.0));
    out.grid->denseFill(
        openvdb::CoordBBox(openvdb::Coord(-25, -25, 25), openvdb::Coord(24, 24, 74)), 1.0f, true);
    out.settings.camera.position = RenderVec3(400, -3800, 700);
    out.settings.camera.lookAt = RenderVec3(0, 0, 1000);
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

/// What a case's reference depends on beyond the scene settings and the sun: its grid's
/// active values (voxels and tiles, with their extent), its transform, its camera and its
/// extinction.
std::string contentKey(const Case& c)
{
    cg::Hasher h;
    const auto vec3 = [&](const openvdb::Vec3d& v) { h.f64(v[0]).f64(v[1]).f64(v[2]); };
    for (auto v = c.grid->cbeginValueOn(); v; ++v) {
        openvdb::CoordBBox box;
        v.getBoundingBox(box);
        for (const openvdb::Coord& corner : {box.min(), box.max()})
            for (int a = 0; a < 3; ++a) h.i64(corner[a]);
        h.f64(*v);
    }
    vec3(c.grid->transform().indexToWorld(openvdb::Vec3d(0.0)));
    vec3(c.grid->transform().indexToWorld(openvdb::Vec3d(1.0)));
    vec3(c.settings.camera.position);
    vec3(c.settings.camera.lookAt);
    vec3(c.settings.camera.up);
    h.f64(c.settings.camera.fovDegrees).f64(c.settings.medium.extinction);
    return h.finish().hex().substr(0, 16);
}

/// Reads a cached image; false (render it again) unless the file holds exactly its floats.
bool readCached(const std::filesystem::path& path, cg::algo::RenderedImage& img)
{
    const std::size_t bytes = img.rgba.size() * sizeof(float);
    std::error_code error;
    if (std::filesystem::file_size(path, error) != bytes || error) return false;
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(img.rgba.data()), static_cast<std::streamsize>(bytes));
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
    std::uint64_t seed = 0;
    std::string pngDir, cacheDir;
    std::vector<Case> cases;
    std::vector<std::pair<std::string, double>> fastSettings, sceneSettings;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            const auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
                return argv[++i];
            };
            if (arg == "--samples")
                samples = std::stoi(value());
            else if (arg == "--size") {
                if (std::sscanf(value().c_str(), "%dx%d", &width, &height) != 2)
                    throw std::runtime_error("--size WxH");
            } else if (arg == "--png")
                pngDir = value();
            else if (arg == "--cache")
                cacheDir = value();
            else if (arg == "--seed")
                seed = std::stoull(value());
            else if (arg == "--fast" || arg == "--scene") {
                const std::string kv = value();
                const auto eq = kv.find('=');
                if (eq == std::string::npos) throw std::runtime_error(arg + " K=V");
                (arg == "--fast" ? fastSettings : sceneSettings)
                    .emplace_back(kv.substr(0, eq), std::stod(kv.substr(eq + 1)));
            } else if (arg == "synthetic")
                cases.push_back(syntheticCase());
            else if (arg == "box")
                cases.push_back(boxCase());
            else
                cases.push_back(fileCase(arg));
        }
        if (cases.empty()) throw std::runtime_error("no case given");
    } catch (const std::exception& e) {
        std::cerr << "render_error: " << e.what() << "\n";
        return 2;
    }

    std::printf(
        "| volume | sun | cloud px | fast / ref | mean error | 90th pct | darker half | "
        "brighter half | reference noise | fast | reference |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (Case& c : cases) {
        const std::string content = cacheDir.empty() ? std::string() : contentKey(c);
        for (const std::string where : {"front", "beside", "behind"}) {
            cg::algo::RenderSettings s = c.settings;
            s.camera.width = width;
            s.camera.height = height;
            s.sun.direction = cg::algo::sunAroundCamera(s.camera, where);
            s.pathTrace.samples = samples;
            s.march.seed = seed;
            std::string sceneTag;  // in the cached reference's name
            for (const auto& [key, v] : sceneSettings) {
                if (key == "ambient")
                    s.sky.ambient = v;
                else if (key == "sun")
                    s.sun.intensity = v;
                else if (key == "haze")
                    s.ground.hazeDistance = v;
                else if (key == "skyRadiance") {
                    s.sky.zenith *= v;
                    s.sky.horizon *= v;
                } else if (key == "ground")
                    s.ground.enabled = v != 0.0;
                else if (key == "groundAlbedo")
                    s.ground.albedo = cg::algo::RenderVec3(v);
                else if (key == "albedo")
                    s.medium.albedo = v;
                else if (key == "bounces")
                    s.pathTrace.maxBounces = static_cast<int>(v);
                else if (key == "mie") {
                    s.medium.phase = cg::algo::PhaseModel::Mie;
                    s.medium.dropletDiameter = v;
                } else
                    throw std::runtime_error("unknown scene setting " + key);
                sceneTag += "_" + key + std::to_string(v);
            }
            cg::algo::RenderSettings fastS = s;
            for (const auto& [key, v] : fastSettings) {
                if (key == "lightTexel")
                    fastS.march.lightTexel = v;
                else if (key == "step")
                    fastS.march.step = v;
                else if (key == "coarseTransmittance")
                    fastS.march.coarseTransmittance = v;
                else if (key == "cellVoxels")
                    fastS.multiScatter.cellVoxels = static_cast<int>(v);
                else if (key == "octaves") {  // the model before the diffusion solve
                    fastS.multiScatter.model = cg::algo::MultiScatterModel::Octaves;
                    fastS.multiScatter.octaves = static_cast<int>(v);
                } else
                    throw std::runtime_error("unknown fast setting " + key);
            }

            auto start = std::chrono::steady_clock::now();
            const cg::algo::RenderedImage fast = cg::algo::renderFogVolume(*c.grid, fastS);
            const double fastSeconds = seconds(start);

            // The reference is the mean of two independent halves (seeds 2·seed and 2·seed + 1),
            // and the halves' disagreement measures how far it is from converged.
            double refSeconds = 0.0;
            const auto renderHalf = [&](int which) {
                cg::algo::RenderSettings h = s;
                h.pathTrace.samples = std::max(1, samples / 2);
                h.march.seed = 2 * seed + static_cast<std::uint64_t>(which);
                const std::filesystem::path cached =
                    cacheDir.empty() ? std::filesystem::path()
                                     : std::filesystem::path(cacheDir) /
                                           (c.name + "-" + content + "_" + where + "_" +
                                            std::to_string(width) + "x" + std::to_string(height) +
                                            sceneTag + "_" + std::to_string(h.pathTrace.samples) +
                                            "_seed" + std::to_string(h.march.seed) + ".f32");
                cg::algo::RenderedImage img;
                img.width = width;
                img.height = height;
                img.rgba.resize(fast.rgba.size());
                if (cached.empty() || !readCached(cached, img)) {
                    const auto t0 = std::chrono::steady_clock::now();
                    img = cg::algo::renderPathTraced(*c.grid, h);
                    refSeconds += seconds(t0);
                    if (!cached.empty()) {
                        std::filesystem::create_directories(cacheDir);
                        writeCached(cached, img);
                    }
                }
                return img;
            };
            const cg::algo::RenderedImage refA = renderHalf(0), refB = renderHalf(1);
            cg::algo::RenderedImage ref = refA;
            for (std::size_t i = 0; i < ref.rgba.size(); ++i)
                ref.rgba[i] = 0.5f * (refA.rgba[i] + refB.rgba[i]);
            const cg::algo::LuminanceError e = cg::algo::luminanceError(fast, ref);
            std::printf(
                "| %s | %s | %zu | %.2f | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% | "
                "%.3f s | %s |\n",
                c.name.c_str(), where.c_str(), e.pixels, e.ratio, 100 * e.mean, 100 * e.p90,
                100 * e.darkMean, 100 * e.brightMean, 100 * cg::algo::referenceNoise(refA, refB),
                fastSeconds,
                refSeconds > 0.0 ? (std::to_string(refSeconds) + " s").c_str() : "cached");
            std::fflush(stdout);
            if (!pngDir.empty()) {
                std::filesystem::create_directories(pngDir);
                const std::string stem = pngDir + "/" + c.name + "_" + where;
                writeSideBySide(stem + ".png", fast, ref);
                writeCached(stem + "_fast.f32", fast);  // floats, for a closer look
                writeCached(stem + "_reference.f32", ref);
            }
        }
    }
    return 0;
}
