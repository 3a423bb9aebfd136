#include "nodes/render/CameraParams.h"

#include <stdexcept>
#include <string>

#include "algo/render/CameraMatrices.h"
#include "core/Hash.h"
#include "formats/ChanFile.h"
#include "formats/FileHash.h"
#include "formats/FormatError.h"

namespace cg {

namespace {

algo::RenderVec3 vec(const ParamSet& p, const char* name)
{
    const Vec3 v = p.getVec3(name);
    return {v[0], v[1], v[2]};
}

std::vector<algo::CameraKey> keysFromFile(const ParamSet& p)
{
    std::vector<algo::CameraKey> keys;
    for (const formats::ChanLine& line : formats::readChan(p.getString("cameraFile"))) {
        algo::NukePose pose;
        pose.translate = {line.translate[0], line.translate[1], line.translate[2]};
        pose.rotateDegrees = {line.rotateDegrees[0], line.rotateDegrees[1], line.rotateDegrees[2]};
        pose.verticalFovDegrees =
            line.verticalFovDegrees > 0.0 ? line.verticalFovDegrees : p.getFloat("fov");
        keys.push_back(algo::keyFromNukePose(static_cast<double>(line.frame), pose));
    }
    return keys;
}

std::vector<algo::CameraKey> keysFromList(const ParamSet& p)
{
    const std::vector<double>& v = p.getFloatList("cameraKeys");
    if (v.size() % kNumbersPerCameraKey != 0)
        throw std::invalid_argument(
            "cameraKeys holds " + std::to_string(v.size()) +
            " numbers; each key is 8: frame, position x y z, look-at x y z, field of view");
    std::vector<algo::CameraKey> keys;
    for (std::size_t i = 0; i < v.size(); i += kNumbersPerCameraKey) {
        algo::CameraKey k;
        k.frame = v[i];
        k.position = {v[i + 1], v[i + 2], v[i + 3]};
        k.lookAt = {v[i + 4], v[i + 5], v[i + 6]};
        k.up = vec(p, "cameraUp");
        k.fovDegrees = v[i + 7];
        keys.push_back(k);
    }
    return keys;
}

}  // namespace

std::vector<algo::CameraKey> cameraKeysFrom(const ParamSet& p)
{
    std::vector<algo::CameraKey> keys;
    if (!p.getString("cameraFile").empty()) {
        keys = keysFromFile(p);
    } else if (!p.getFloatList("cameraKeys").empty()) {
        keys = keysFromList(p);
    } else {
        algo::CameraKey k;
        k.position = vec(p, "cameraPosition");
        k.lookAt = vec(p, "cameraLookAt");
        k.up = vec(p, "cameraUp");
        k.fovDegrees = p.getFloat("fov");
        keys.push_back(k);
    }
    algo::checkCameraKeys(keys);
    return keys;
}

void checkCameraParams(const ParamSet& p, const ParamChecker& check)
{
    const bool file = !p.getString("cameraFile").empty();
    const bool keys = !p.getFloatList("cameraKeys").empty();
    try {
        cameraKeysFrom(p);
    } catch (const std::invalid_argument& e) {
        if (file || keys) check.fail(file ? "cameraFile" : "cameraKeys", e.what());
        // A still camera is one key to the path, not one the user wrote.
        std::string what = e.what();
        const std::string key0 = "camera key 0: ";
        if (what.rfind(key0, 0) == 0) what = "the camera: " + what.substr(key0.size());
        const char* param = what.find("its up") != std::string::npos          ? "cameraUp"
                            : what.find("field of view") != std::string::npos ? "fov"
                                                                              : "cameraLookAt";
        check.fail(param, what);
    }
}

void hashCameraFile(const ParamSet& p, Hasher& h)
{
    const std::string& file = p.getString("cameraFile");
    if (file.empty()) return;
    try {
        h.str("cameraFile")
            .u64(formats::fileContentHash(file, formats::kMaxChanBytes, "camera file"));
    } catch (const formats::FormatError&) {
        h.str("unreadable camera file").str(file);
    }
}

}  // namespace cg
