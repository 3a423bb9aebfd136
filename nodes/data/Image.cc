/// Image's stored form, version 4, in ByteWriter's primitives (u64 little-endian; a float
/// vector is a u64 count and the floats' bytes; f64 a double's bytes):
///
///   8 bytes  tag "CGIMAGE4" (versions 1 to 3, without the camera or the AOVs: refused)
///   u64      width, u64 height, each 1 to 2^20
///   floats   rgba: 4 per pixel, top row first, finite
///   floats   background: none, or 3 per pixel, top row first, finite
///   u64      1 when a camera follows, else 0
///   f64 x 10 camera: position, look-at, up (x, y, z each), vertical field of view in
///            degrees; finite, the field of view in (0, 180), not looking at itself
///   floats   AOVs sun, sky (3 per pixel), depth, shadow (1 per pixel): all four empty, or
///            all four full; finite

#include "nodes/data/Image.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "Image";
constexpr char kTag[8] = {'C', 'G', 'I', 'M', 'A', 'G', 'E', '4'};
constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20;

/// Every value finite: the renderer makes finite radiance, and the writers' tone map,
/// quantisation and cloud layer assume it.
void requireFinite(const std::vector<float>& values, std::size_t channels, const char* what)
{
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            checks::refuse(kType, std::string(what) + "channel " + std::to_string(i % channels) +
                                      " of pixel " + std::to_string(i / channels) +
                                      " is not finite");
}

/// Whether full AOVs have the sizes of `pixels` pixels.
bool aovsFit(const ImageAovs& a, std::uint64_t pixels)
{
    return a.sun.size() == 3 * pixels && a.sky.size() == 3 * pixels && a.depth.size() == pixels &&
           a.shadow.size() == pixels;
}

algo::RenderVec3 readVector(ByteReader& in)
{
    const double x = in.f64(), y = in.f64(), z = in.f64();
    return {x, y, z};
}

/// The camera that follows the pixels, if any, checked as the renderer would use it.
std::optional<algo::RenderCamera> readCamera(ByteReader& in, std::uint64_t w, std::uint64_t h)
{
    const std::uint64_t present = in.u64();
    if (present == 0) return std::nullopt;
    if (present != 1) checks::refuse(kType, "camera flag " + std::to_string(present));
    algo::RenderCamera c;
    c.position = readVector(in);
    c.lookAt = readVector(in);
    c.up = readVector(in);
    c.fovDegrees = in.f64();
    c.width = static_cast<int>(w);
    c.height = static_cast<int>(h);
    for (const algo::RenderVec3& v : {c.position, c.lookAt, c.up})
        if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
            checks::refuse(kType, "a camera vector is not finite");
    if (!(c.fovDegrees > 0.0 && c.fovDegrees < 180.0))
        checks::refuse(kType, "the camera's field of view is not in (0, 180)");
    if (c.position == c.lookAt) checks::refuse(kType, "the camera looks at its own position");
    return c;
}

DataPtr readImage(ByteReader& in)
{
    char tag[8];
    in.bytes(tag, 8);
    if (std::memcmp(tag, kTag, 8) != 0)
        checks::refuse(kType, "not a version 4 image (no CGIMAGE4 tag)");
    const std::uint64_t w = in.u64();
    const std::uint64_t h = in.u64();
    auto rgba = in.podVector<float>();
    auto background = in.podVector<float>();
    if (w == 0 || h == 0 || w > kMaxSide || h > kMaxSide)
        checks::refuse(kType,
                       "size " + std::to_string(w) + " x " + std::to_string(h) + " is absurd");
    if (rgba.size() != 4 * w * h)
        checks::refuse(kType, std::to_string(rgba.size()) + " floats for " + std::to_string(w) +
                                  " x " + std::to_string(h) + " RGBA pixels");
    if (!background.empty() && background.size() != 3 * w * h)
        checks::refuse(kType, std::to_string(background.size()) + " background floats for " +
                                  std::to_string(w) + " x " + std::to_string(h) + " RGB pixels");
    requireFinite(rgba, 4, "");
    requireFinite(background, 3, "background ");
    std::optional<algo::RenderCamera> camera = readCamera(in, w, h);
    ImageAovs aovs;
    aovs.sun = in.podVector<float>();
    aovs.sky = in.podVector<float>();
    aovs.depth = in.podVector<float>();
    aovs.shadow = in.podVector<float>();
    if (!aovs.empty() && !aovsFit(aovs, w * h))
        checks::refuse(kType, "the AOVs' sizes do not match " + std::to_string(w) + " x " +
                                  std::to_string(h) + " pixels");
    requireFinite(aovs.sun, 3, "sun ");
    requireFinite(aovs.sky, 3, "sky ");
    requireFinite(aovs.depth, 1, "depth ");
    requireFinite(aovs.shadow, 1, "shadow ");
    return std::make_shared<ImageData>(static_cast<int>(w), static_cast<int>(h), std::move(rgba),
                                       std::move(background), camera, std::move(aovs));
}

}  // namespace

ImageData::ImageData(int width_, int height_, std::vector<float> rgba_,
                     std::vector<float> background_, std::optional<algo::RenderCamera> camera_,
                     ImageAovs aovs_)
    : width(width_),
      height(height_),
      rgba(std::move(rgba_)),
      background(std::move(background_)),
      camera(camera_),
      aovs(std::move(aovs_))
{
    const std::size_t pixels =
        width > 0 && height > 0 ? static_cast<std::size_t>(width) * static_cast<std::size_t>(height)
                                : 0;
    if (pixels == 0 || rgba.size() != 4 * pixels)
        throw std::invalid_argument("Image: size does not match its pixels");
    if (!background.empty() && background.size() != 3 * pixels)
        throw std::invalid_argument("Image: background size does not match its pixels");
    if (!aovs.empty() && !aovsFit(aovs, pixels))
        throw std::invalid_argument("Image: AOV sizes do not match its pixels");
}

bool ImageData::serialize(ByteWriter& out) const
{
    out.bytes(kTag, 8);
    out.u64(static_cast<std::uint64_t>(width));
    out.u64(static_cast<std::uint64_t>(height));
    out.podVector(rgba);
    out.podVector(background);
    out.u64(camera ? 1 : 0);
    if (camera) {
        for (const algo::RenderVec3& v : {camera->position, camera->lookAt, camera->up})
            for (int a = 0; a < 3; ++a) out.f64(v[a]);
        out.f64(camera->fovDegrees);
    }
    for (const std::vector<float>* v : {&aovs.sun, &aovs.sky, &aovs.depth, &aovs.shadow})
        out.podVector(*v);
    return true;
}

void registerImageType(Registry& registry)
{
    registry.addDataType({"Image",
                          "an image: float RGBA pixels, top row first, and optionally the "
                          "radiance behind a rendered volume (RGB)",
                          readImage});
}

}  // namespace cg
