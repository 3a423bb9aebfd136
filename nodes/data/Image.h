#pragma once
/// A rendered image: float RGBA, row-major from the top row down. The renderer documents
/// whether its output is linear radiance or already tone-mapped.

#include <optional>
#include <vector>

#include "algo/render/RenderSettings.h"
#include "core/Data.h"

namespace cg {

class Registry;

/// A renderer's AOVs (algo::RenderedImage has their definitions), top row first: all empty,
/// or sun and sky 3 floats per pixel, depth and shadow 1.
struct ImageAovs {
    std::vector<float> sun, sky, depth, shadow;
    bool empty() const { return sun.empty() && sky.empty() && depth.empty() && shadow.empty(); }
};

class ImageData final : public Data {
public:
    /// `background` is empty, or 3 floats per pixel. Throws std::invalid_argument if a size
    /// does not match width x height.
    ImageData(int width, int height, std::vector<float> rgba, std::vector<float> background = {},
              std::optional<algo::RenderCamera> camera = std::nullopt, ImageAovs aovs = {});

    const int width;
    const int height;
    const std::vector<float> rgba;  ///< 4 floats per pixel, top row first
    /// Optional, a renderer's: 3 floats (linear RGB) per pixel, top row first, the radiance
    /// behind the volume, so rgba = cloud + (1 - alpha) background
    /// (algo/render/image/CloudLayer.h). Empty for images that have none.
    const std::vector<float> background;

    /// Optional, a renderer's: the camera the image was rendered with (its width and height
    /// are the image's), for the writers' camera metadata.
    const std::optional<algo::RenderCamera> camera;

    /// Optional, a renderer's (Renderer aovs): the cloud's light from the sun and from the
    /// sky, depth, ground shadow matte.
    const ImageAovs aovs;

    bool hasBackground() const { return !background.empty(); }
    std::string typeName() const override { return "Image"; }
    std::size_t byteSize() const override
    {
        return sizeof(*this) + (rgba.size() + background.size() + aovs.sun.size() +
                                aovs.sky.size() + aovs.depth.size() + aovs.shadow.size()) *
                                   sizeof(float);
    }
    bool serialize(ByteWriter& out) const override;
};

void registerImageType(Registry& registry);

}  // namespace cg
