#include "formats/PrimitivePly.h"

#include <cstdio>

#include "formats/PlyWriter.h"
#include "util/FramePattern.h"

namespace cg::formats {

void writePrimitiveFramePly(const std::filesystem::path& path, const float* positions,
                            std::uint32_t count, int frame, const std::function<void()>& poll)
{
    std::vector<float> x(count), y(count), z(count), zero(count, 0.0f);
    std::vector<std::uint32_t> id(count), home(count, 0u);
    std::vector<std::int32_t> state(count, 1);
    for (std::uint32_t i = 0; i < count; ++i) {
        x[i] = positions[3 * std::size_t{i}];
        y[i] = positions[3 * std::size_t{i} + 1];
        z[i] = positions[3 * std::size_t{i} + 2];
        id[i] = i;
    }
    PlyParticleView view;
    view.count = count;
    view.x = x.data();
    view.y = y.data();
    view.z = z.data();
    view.vz = zero.data();
    view.temperature = zero.data();
    view.id = id.data();
    view.state = state.data();
    view.homeCell = home.data();
    writeParticlesPly(path, view, "primitive set frame " + std::to_string(frame), poll);
}

std::filesystem::path primitiveFramePath(const std::filesystem::path& pattern, int frame)
{
    if (util::firstHashRun(pattern.filename().string())) return util::framePath(pattern, frame);
    const std::string stem = pattern.stem().string(), ext = pattern.extension().string();
    return util::framePath(pattern.parent_path() / (stem + ".####" + ext), frame);
}

}  // namespace cg::formats
