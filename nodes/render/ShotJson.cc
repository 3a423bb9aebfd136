#include "nodes/render/ShotJson.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "algo/render/media/Phase.h"
#include "nodes/data/CameraPath.h"

namespace cg {

namespace {

nlohmann::json vec(const algo::RenderVec3& v) { return {v.x(), v.y(), v.z()}; }

const char* phaseName(algo::PhaseModel m)
{
    return m == algo::PhaseModel::Mie ? "mie" : "twoLobeHG";
}

}  // namespace

std::string lightingJson(const algo::RenderSettings& s)
{
    const nlohmann::json j = {
        {"sun",
         {{"direction", vec(s.sun.direction.unit())},
          {"colour", vec(s.sun.colour)},
          {"irradiance", s.sun.intensity}}},
        {"sky",
         {{"zenith", vec(s.sky.zenith)},
          {"horizon", vec(s.sky.horizon)},
          {"gradient", "horizon + (zenith - horizon) sqrt(z), horizon below"},
          {"ambient", s.sky.ambient}}},
        {"ground",
         {{"enabled", s.ground.enabled},
          {"albedo", vec(s.ground.albedo)},
          {"haze_distance_m", s.ground.hazeDistance}}},
        {"medium",
         {{"extinction_per_unit", s.medium.extinction},
          {"albedo", s.medium.albedo},
          {"phase", phaseName(s.medium.phase)},
          {"g", s.medium.g},
          {"g2", s.medium.g2},
          {"lobe_blend", s.medium.lobeBlend},
          {"droplet_diameter_um", s.medium.dropletDiameter},
          {"mean_cosine", algo::phaseOf(s.medium).meanCosine()}}},
    };
    return j.dump();
}

std::string shotJson(const CameraPathData& path, int first, int last, double frameTime,
                     const std::string& lighting)
{
    const nlohmann::json light = nlohmann::json::parse(lighting, nullptr, false);
    if (!light.is_object())
        throw std::invalid_argument("the lighting is not a JSON object (the Renderer's output)");
    nlohmann::json cameras = nlohmann::json::array();
    for (int frame = first; frame <= last; ++frame) {
        const algo::RenderCamera c = path.at(frame);
        cameras.push_back({{"frame", frame},
                           {"position", vec(c.position)},
                           {"look_at", vec(c.lookAt)},
                           {"up", vec(c.up)},
                           {"vertical_fov_deg", c.fovDegrees}});
    }
    // One line a key, a camera a line: a 500-frame shot stays a file one can read.
    const std::pair<const char*, nlohmann::json> fields[] = {
        {"cloudgraph_shot", 1},
        {"units", "metres, z up; linear Rec.709 radiance; degrees"},
        {"frames", {{"start", first}, {"end", last}}},
        {"frame_time_s", frameTime},
        {"image", {{"width", path.width}, {"height", path.height}}},
        {"lighting", light},
    };
    std::string text = "{\n";
    for (const auto& [key, value] : fields)
        text += "  " + nlohmann::json(key).dump() + ": " + value.dump() + ",\n";
    text += "  \"camera\": [\n";
    for (std::size_t i = 0; i < cameras.size(); ++i)
        text += "    " + cameras[i].dump() + (i + 1 < cameras.size() ? ",\n" : "\n");
    return text + "  ]\n}\n";
}

}  // namespace cg
