#include "nodes/data/Image.h"

#include <stdexcept>

#include "core/Registry.h"

namespace cg {

ImageData::ImageData(int width_, int height_, std::vector<float> rgba_)
    : width(width_), height(height_), rgba(std::move(rgba_))
{
    if (width <= 0 || height <= 0 ||
        rgba.size() != 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw std::invalid_argument("Image: size does not match its pixels");
}

bool ImageData::serialize(ByteWriter& out) const
{
    out.u64(static_cast<std::uint64_t>(width));
    out.u64(static_cast<std::uint64_t>(height));
    out.podVector(rgba);
    return true;
}

void registerImageType(Registry& registry)
{
    registry.addDataType({"Image", "an image: float RGBA pixels, top row first",
                          [](ByteReader& in) -> DataPtr {
                              const auto w = in.u64();
                              const auto h = in.u64();
                              if (w > (1u << 20) || h > (1u << 20))
                                  throw std::runtime_error("Image: absurd size");
                              auto rgba = in.podVector<float>();
                              return std::make_shared<ImageData>(static_cast<int>(w),
                                                                 static_cast<int>(h), std::move(rgba));
                          }});
}

}  // namespace cg
