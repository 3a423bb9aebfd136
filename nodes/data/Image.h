#pragma once
/// A rendered image: float RGBA, row-major from the top row down. The renderer documents
/// whether its output is linear radiance or already tone-mapped.

#include <vector>

#include "core/Data.h"

namespace cg {

class Registry;

class ImageData final : public Data {
public:
    ImageData(int width, int height, std::vector<float> rgba);

    const int width;
    const int height;
    const std::vector<float> rgba;  ///< 4 floats per pixel, top row first

    std::string typeName() const override { return "Image"; }
    std::size_t byteSize() const override { return sizeof(*this) + rgba.size() * sizeof(float); }
    bool serialize(ByteWriter& out) const override;
};

void registerImageType(Registry& registry);

}  // namespace cg
