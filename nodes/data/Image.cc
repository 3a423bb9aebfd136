#include "nodes/data/Image.h"

#include <cmath>
#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "Image";
constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20;

DataPtr readImage(ByteReader& in)
{
    const std::uint64_t w = in.u64();
    const std::uint64_t h = in.u64();
    auto rgba = in.podVector<float>();
    if (w == 0 || h == 0 || w > kMaxSide || h > kMaxSide)
        checks::refuse(kType,
                       "size " + std::to_string(w) + " x " + std::to_string(h) + " is absurd");
    if (rgba.size() != 4 * w * h)
        checks::refuse(kType, std::to_string(rgba.size()) + " floats for " + std::to_string(w) +
                                  " x " + std::to_string(h) + " RGBA pixels");
    // The renderer makes finite radiance; the writers' tone map and quantisation assume it.
    for (std::size_t i = 0; i < rgba.size(); ++i)
        if (!std::isfinite(rgba[i]))
            checks::refuse(kType, "channel " + std::to_string(i % 4) + " of pixel " +
                                      std::to_string(i / 4) + " is not finite");
    return std::make_shared<ImageData>(static_cast<int>(w), static_cast<int>(h), std::move(rgba));
}

}  // namespace

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
    registry.addDataType({"Image", "an image: float RGBA pixels, top row first", readImage});
}

}  // namespace cg
