// How real a fog volume's clouds look, by cloud physics' measures (algo/volume/CloudMetrics.h):
// side-outline and area-perimeter fractal dimensions, top-edge sharpness, base flatness.
//
// Usage: cloud_metrics [--extinction E] [--condensation-level Z] [--side-png F] file.vdb [...]
//
// The extinction (1/m per unit of the grid's value) is the grid's `extinction` metadata when
// it has one, else --extinction (default 0.02, the Renderer's default). With
// --condensation-level, the median base's distance from it is printed as a share of the
// cloud's depth. --side-png writes the side view's optical depth as a grey image (white =
// tau >= 1, the cloud the outline is measured on; grey 1 - exp(-tau) below), top row highest.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "algo/volume/CloudMetrics.h"
#include "formats/PngFile.h"

namespace {

double extinctionOf(const openvdb::FloatGrid& grid, double fallback)
{
    if (const auto m = grid.getMetadata<openvdb::FloatMetadata>("extinction")) return m->value();
    if (const auto m = grid.getMetadata<openvdb::DoubleMetadata>("extinction")) return m->value();
    return fallback;
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

void report(const std::string& path, double extinction, double condensationLevel,
            const std::string& sidePng)
{
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
}

}  // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    double extinction = 0.02;
    double condensationLevel = std::nan("");
    std::string sidePng;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--extinction" && i + 1 < argc)
            extinction = std::atof(argv[++i]);
        else if (a == "--condensation-level" && i + 1 < argc)
            condensationLevel = std::atof(argv[++i]);
        else if (a == "--side-png" && i + 1 < argc)
            sidePng = argv[++i];
        else
            files.push_back(a);
    }
    if (files.empty()) {
        std::cerr << "usage: cloud_metrics [--extinction E] [--condensation-level Z] file.vdb...\n";
        return 2;
    }
    try {
        for (const auto& f : files) report(f, extinction, condensationLevel, sidePng);
    } catch (const std::exception& e) {
        std::cerr << "cloud_metrics: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
