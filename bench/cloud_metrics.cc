// How real a fog volume's clouds look, by cloud physics' measures (algo/volume/CloudMetrics.h):
// side-outline and area-perimeter fractal dimensions, top-edge sharpness, base flatness.
//
// Usage: cloud_metrics [--extinction E] [--condensation-level Z] [--side-png F] [--sizes]
//                      [--domain X0,Y0,X1,Y1] [--track] file.vdb [...]
//
// The extinction (1/m per unit of the grid's value) is the grid's `extinction` metadata when
// it has one, else --extinction (default 0.02, the Renderer's default). With
// --condensation-level, the median base's distance from it is printed as a share of the
// cloud's depth. --side-png writes the side view's optical depth as a grey image (white =
// tau >= 1, the cloud the outline is measured on; grey 1 - exp(-tau) below), top row highest.
//
// Seen from above, each file's clouds (4-connected columns of tau >= 1, at least 4) give a
// size density n(l), l = sqrt(area), in bins a factor sqrt(2) wide from 2 voxels, and its
// power-law exponent fitted over the bins of at least 24 clouds (algo/volume/SizeDensity.h);
// --sizes prints the bins. --domain (m) gives the cover: the share of the rectangle's columns
// that are cloud. --track reads the files as one field at successive times and prints how many
// of the first file's clouds are gone by the last, and how many of the last's are new
// (algo/volume/CloudTracking.h; the drift between files is searched up to 32 columns).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "algo/volume/CloudMetrics.h"
#include "algo/volume/CloudTracking.h"
#include "algo/volume/SizeDensity.h"
#include "formats/PngFile.h"

namespace {

double extinctionOf(const openvdb::FloatGrid& grid, double fallback)
{
    if (const auto m = grid.getMetadata<openvdb::FloatMetadata>("extinction")) return m->value();
    if (const auto m = grid.getMetadata<openvdb::DoubleMetadata>("extinction")) return m->value();
    return fallback;
}

/// "a,b,c" as numbers.
std::vector<double> parseList(const std::string& text)
{
    std::vector<double> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        out.push_back(std::atof(text.substr(start, comma - start).c_str()));
        start = comma + 1;
    }
    return out;
}

/// The side view as an 8-bit grey PNG, highest row first.
void writeSidePng(const std::string& path, const cg::algo::SideView& side)
{
    std::vector<std::uint8_t> grey;
    grey.reserve(side.tau.size());
    for (int row = side.height - 1; row >= 0; --row)
        for (int x = 0; x < side.width; ++x) {
            const double tau = side.tau[static_cast<std::size_t>(row) * side.width + x];
            const double g = tau >= 1.0 ? 1.0 : 0.8 * (1.0 - std::exp(-tau));
            grey.push_back(static_cast<std::uint8_t>(255.0 * g + 0.5));
        }
    std::vector<const unsigned char*> rows;
    for (int row = 0; row < side.height; ++row)
        rows.push_back(grey.data() + static_cast<std::size_t>(row) * side.width);
    cg::formats::writePng(path, side.width, side.height, 1, 8, rows, false);
}

struct Options {
    double extinction = 0.02;
    double condensationLevel = std::nan("");
    std::string sidePng;
    bool sizes = false, track = false;
    std::vector<double> domain;  // x0, y0, x1, y1 in m, or empty
};

constexpr double kMinCloudColumns = 4;
constexpr std::size_t kMinBinClouds = 24;
constexpr int kMaxDriftColumns = 32;

/// The clouds seen from above: their size density and, with a domain, the cover.
void reportField(const cg::algo::CoverFrame& cover, double voxel, const Options& o)
{
    std::vector<double> sizes;
    for (const double a : cover.regions.area) sizes.push_back(std::sqrt(a) * voxel);
    const auto fit = cg::algo::fitSizeDensity(sizes, std::sqrt(kMinCloudColumns) * voxel,
                                              std::sqrt(2.0), kMinBinClouds);
    std::printf("  size density exponent       %.2f over %zu bins of >= %zu clouds\n", fit.exponent,
                fit.fittedBins, kMinBinClouds);
    if (o.sizes)
        for (const auto& b : fit.bins)
            std::printf("    l %6.0f-%6.0f m  %5zu clouds  n %.3g /m\n", b.lo, b.hi, b.count,
                        b.density);
    if (o.domain.size() == 4)
        std::printf("  cover                       %.1f%% of the domain\n",
                    100.0 * cg::algo::coverShare(cover, voxel, o.domain[0], o.domain[1],
                                                 o.domain[2], o.domain[3]));
}

cg::algo::CoverFrame report(const std::string& path, const Options& o, double& voxel)
{
    const double extinction = o.extinction;
    const double condensationLevel = o.condensationLevel;
    const std::string& sidePng = o.sidePng;
    openvdb::io::File file(path);
    file.open();
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    file.close();
    if (!grid) throw std::runtime_error(path + ": 'density' is not a float grid");
    cg::algo::CloudMetricsOptions options;
    options.extinction = extinctionOf(*grid, extinction);
    const cg::algo::CloudMetrics m = cg::algo::measureCloud(*grid, options);
    if (!sidePng.empty())
        writeSidePng(sidePng, cg::algo::sideOpticalDepth(*grid, options.extinction));
    std::printf("%s (extinction %.4g /m, voxel %.3g m)\n", path.c_str(), options.extinction,
                m.voxelSize);
    std::printf("  side outline dimension      %.3f\n", m.sideOutlineDimension);
    std::printf("  top edge tau 0.1-2 (m)      median %.0f, p90 %.0f over %zu thick columns\n",
                m.topEdgeMedian, m.topEdgeP90, m.thickColumns);
    std::printf("  base (m)                    p10 %.0f, median %.0f, p90 %.0f; top %.0f\n",
                m.baseP10, m.baseMedian, m.baseP90, m.top);
    std::printf("  base spread                 %.1f%% of the depth over %zu columns\n",
                100.0 * m.baseSpread, m.cloudColumns);
    if (std::isfinite(condensationLevel))
        std::printf("  median base - condensation  %.1f%% of the depth\n",
                    100.0 * (m.baseMedian - condensationLevel) / (m.top - m.baseMedian));
    std::printf("  area-perimeter dimension    %.3f over %zu clouds seen from above\n",
                m.areaPerimeterDimension, m.clouds);
    voxel = m.voxelSize;
    cg::algo::CoverFrame cover =
        cg::algo::coverOf(cg::algo::topOpticalDepth(*grid, options.extinction));
    reportField(cover, voxel, o);
    return cover;
}

void reportTurnover(const std::vector<cg::algo::CoverFrame>& frames, double voxel)
{
    const auto t = cg::algo::trackTurnover(frames, kMaxDriftColumns, kMinCloudColumns);
    std::printf("tracked over %zu files:\n", frames.size());
    for (std::size_t k = 0; k < t.drifts.size(); ++k)
        std::printf(
            "  drift %zu->%zu                  (%.0f, %.0f) m, %zu cloud columns coincide\n", k,
            k + 1, t.drifts[k].dx * voxel, t.drifts[k].dy * voxel, t.drifts[k].overlap);
    std::printf("  gone                        %zu of the first file's %zu clouds (%.0f%%)\n",
                t.gone, t.firstClouds,
                100.0 * static_cast<double>(t.gone) / static_cast<double>(t.firstClouds));
    std::printf("  new                         %zu of the last file's %zu clouds (%.0f%%)\n",
                t.born, t.lastClouds,
                100.0 * static_cast<double>(t.born) / static_cast<double>(t.lastClouds));
}

}  // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    Options o;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--extinction" && i + 1 < argc)
            o.extinction = std::atof(argv[++i]);
        else if (a == "--condensation-level" && i + 1 < argc)
            o.condensationLevel = std::atof(argv[++i]);
        else if (a == "--side-png" && i + 1 < argc)
            o.sidePng = argv[++i];
        else if (a == "--sizes")
            o.sizes = true;
        else if (a == "--track")
            o.track = true;
        else if (a == "--domain" && i + 1 < argc)
            o.domain = parseList(argv[++i]);
        else
            files.push_back(a);
    }
    if (!o.domain.empty() &&
        (o.domain.size() != 4 || !(o.domain[2] > o.domain[0]) || !(o.domain[3] > o.domain[1]))) {
        std::cerr << "cloud_metrics: --domain wants X0,Y0,X1,Y1 with X1 > X0 and Y1 > Y0\n";
        return 2;
    }
    if (files.empty()) {
        std::cerr << "usage: cloud_metrics [--extinction E] [--condensation-level Z] file.vdb...\n";
        return 2;
    }
    try {
        std::vector<cg::algo::CoverFrame> frames;
        double voxel = 0;
        for (const auto& f : files) frames.push_back(report(f, o, voxel));
        if (o.track && frames.size() >= 2) reportTurnover(frames, voxel);
    } catch (const std::exception& e) {
        std::cerr << "cloud_metrics: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
