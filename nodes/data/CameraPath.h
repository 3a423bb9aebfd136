#pragma once
/// A Renderer's camera over the whole shot: its keys (one key for a camera that does not
/// move) and the image size, so a writer can give the camera of any frame
/// (algo/render/CameraPath.h) without rendering it.

#include <vector>

#include "algo/render/CameraPath.h"
#include "core/Data.h"

namespace cg {

class Registry;

class CameraPathData final : public Data {
public:
    /// Throws std::invalid_argument for unusable keys (algo::checkCameraKeys) or a size < 1.
    CameraPathData(std::vector<algo::CameraKey> keys, int width, int height, bool easeEnds = false);

    const std::vector<algo::CameraKey> keys;
    const int width;
    const int height;
    const bool easeEnds;  ///< the path starts and ends at rest (algo::cameraOnPath)

    /// The camera at `frame`.
    algo::RenderCamera at(double frame) const;

    std::string typeName() const override { return "CameraPath"; }
    std::size_t byteSize() const override
    {
        return sizeof(*this) + keys.size() * sizeof(algo::CameraKey);
    }
    bool serialize(ByteWriter& out) const override;
};

void registerCameraPathType(Registry& registry);

}  // namespace cg
