// How real a fog volume's clouds look, by cloud physics' measures (algo/volume/CloudMetrics.h):
// side-outline and area-perimeter fractal dimensions, top-edge sharpness, base flatness.
//
// Usage: cloud_metrics [--extinction E] [--condensation-level Z] file.vdb [...]
//
// The extinction (1/m per unit of the grid's value) is the grid's `extinction` metadata when
// it has one, else --extinction (default 0.02, the Renderer's default). With
// --condensation-level, the median base's distance from it is printed as a share of the
// cloud's depth.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "algo/volume/CloudMetrics.h"

namespace {

double extinctionOf(const openvdb::FloatGrid& grid, double fallback)
{
    if (const auto m = grid.getMetadata<openvdb::FloatMetadata>("extinction")) return m->value();
    if (const auto m = grid.getMetadata<openvdb::DoubleMetadata>("extinction")) return m->value();
    return fallback;
}

void report(const std::string& path, double extinction, double condensationLevel)
{
    openvdb::io::File file(path);
    file.open();
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    file.close();
    if (!grid) throw std::runtime_error(path + ": 'density' is not a float grid");
    cg::algo::CloudMetricsOptions options;
    options.extinction = extinctionOf(*grid, extinction);
    const cg::algo::CloudMetrics m = cg::algo::measureCloud(*grid, options);
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
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--extinction" && i + 1 < argc)
            extinction = std::atof(argv[++i]);
        else if (a == "--condensation-level" && i + 1 < argc)
            condensationLevel = std::atof(argv[++i]);
        else
            files.push_back(a);
    }
    if (files.empty()) {
        std::cerr << "usage: cloud_metrics [--extinction E] [--condensation-level Z] file.vdb...\n";
        return 2;
    }
    try {
        for (const auto& f : files) report(f, extinction, condensationLevel);
    } catch (const std::exception& e) {
        std::cerr << "cloud_metrics: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
