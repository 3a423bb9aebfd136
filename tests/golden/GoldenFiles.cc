#include "golden/GoldenFiles.h"

#include <cstdint>
#include <fstream>
#include <map>
#include <string>

#include "formats/MapImage.h"
#include "formats/PngFile.h"

namespace cg::golden {

namespace {

/// WriteImage's 8-bit RGB frames (mean code value per channel) or WriteMap's 16-bit grey
/// previews (mean value).
void png(Stats& s, const std::string& path)
{
    formats::PngPixels px;
    try {
        px = formats::readPng(path, 3, 8, 1u << 14);
    } catch (const std::runtime_error&) {
        const formats::MapImage grey = formats::readPng16(path);
        double sum = 0.0;
        for (float v : grey.values) sum += v;
        s["width"] = {Kind::Count, static_cast<double>(grey.nx)};
        s["height"] = {Kind::Count, static_cast<double>(grey.ny)};
        s["mean"] = {Kind::Mean,
                     grey.values.empty() ? 0.0 : sum / static_cast<double>(grey.values.size())};
        return;
    }
    s["width"] = {Kind::Count, static_cast<double>(px.width)};
    s["height"] = {Kind::Count, static_cast<double>(px.height)};
    double sums[3] = {};
    for (std::size_t i = 0; i < px.bytes.size(); ++i) sums[i % 3] += px.bytes[i];
    const double pixels = static_cast<double>(px.bytes.size() / 3);
    const char* channels[] = {"mean_r", "mean_g", "mean_b"};
    for (int c = 0; c < 3; ++c) s[channels[c]] = {Kind::Mean, pixels > 0 ? sums[c] / pixels : 0.0};
}

/// The grid's numeric metadata (frame, particle_count, is_saved_as_half_float, ...) but not
/// OpenVDB's file_* entries, which depend on the library's layout.
void gridMetadata(Stats& s, const std::string& prefix, const openvdb::GridBase& grid)
{
    for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it) {
        const std::string& key = it->first;
        const openvdb::Metadata& m = *it->second;
        if (key.rfind("file_", 0) == 0) continue;
        if (const auto* b = dynamic_cast<const openvdb::BoolMetadata*>(&m))
            s[prefix + key] = {Kind::Count, b->value() ? 1.0 : 0.0};
        else if (const auto* i32 = dynamic_cast<const openvdb::Int32Metadata*>(&m))
            s[prefix + key] = {Kind::Count, static_cast<double>(i32->value())};
        else if (const auto* i64 = dynamic_cast<const openvdb::Int64Metadata*>(&m))
            s[prefix + key] = {Kind::Count, static_cast<double>(i64->value())};
        else if (const auto* f = dynamic_cast<const openvdb::FloatMetadata*>(&m))
            s[prefix + key] = {Kind::Mean, f->value()};
        else if (const auto* d = dynamic_cast<const openvdb::DoubleMetadata*>(&m))
            s[prefix + key] = {Kind::Mean, d->value()};
    }
}

/// Every grid by name, with its metadata; of fog volumes, what writing and reading back must
/// keep (the rest is the Voxelizer's, recorded from its output). Half floats come back
/// widened, and their sums differ from the float grid's by about 1e-7: is_saved_as_half_float
/// says which was written.
void vdb(Stats& s, const std::string& path)
{
    const char* kept[] = {"active_voxels", "value_sum", "value_max", "voxel_size"};
    openvdb::io::File file(path);
    file.open();
    std::int64_t grids = 0;
    for (auto it = file.beginName(); it != file.endName(); ++it, ++grids) {
        const openvdb::GridBase::Ptr base = file.readGrid(it.gridName());
        gridMetadata(s, it.gridName() + "_meta_", *base);
        const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid) continue;
        const Stats all = gridStats(*grid);
        for (const char* name : kept) s[it.gridName() + "_" + name] = all.at(name);
    }
    file.close();
    s["grids"] = {Kind::Count, static_cast<double>(grids)};
}

/// The vertex count from the header: what Blender or Houdini will load.
void ply(Stats& s, const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    for (std::string line; std::getline(in, line) && line != "end_header";)
        if (line.rfind("element vertex ", 0) == 0)
            s["vertices"] = {Kind::Count, static_cast<double>(std::stoll(line.substr(15)))};
}

void pfm(Stats& s, const std::string& path)
{
    const formats::MapImage map = formats::readPfm(path);
    double sum = 0.0;
    for (float v : map.values) sum += v;
    s["nx"] = {Kind::Count, static_cast<double>(map.nx)};
    s["ny"] = {Kind::Count, static_cast<double>(map.ny)};
    s["mean"] = {Kind::Mean,
                 map.values.empty() ? 0.0 : sum / static_cast<double>(map.values.size())};
}

}  // namespace

Stats fileStats(const std::filesystem::path& outDir)
{
    Stats all;
    std::map<std::string, std::int64_t> counts;
    for (const auto& e : std::filesystem::recursive_directory_iterator(outDir)) {
        if (!e.is_regular_file()) continue;
        const std::string dir = e.path().parent_path().lexically_relative(outDir).generic_string();
        const std::string ext = e.path().extension().string();
        const std::string where = "files/" + (dir.empty() ? "." : dir) + "/";
        ++counts[where + "*" + ext];
        Stats s;
        const std::string path = e.path().string();
        if (ext == ".png") png(s, path);
        if (ext == ".vdb") vdb(s, path);
        if (ext == ".ply") ply(s, path);
        if (ext == ".pfm") pfm(s, path);
        for (const auto& [name, stat] : s)
            all[where + e.path().filename().string() + "/" + name] = stat;
    }
    for (const auto& [name, n] : counts) all[name] = {Kind::Count, static_cast<double>(n)};
    return all;
}

}  // namespace cg::golden
