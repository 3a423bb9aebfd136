#include "algo/render/metrics/RenderError.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "algo/render/scenes/SyntheticCumulus.h"

namespace cg::algo {

namespace {

constexpr float kCloudAlpha = 0.5f;

void requireSameSize(const RenderedImage& a, const RenderedImage& b)
{
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        throw std::invalid_argument("images of different sizes");
}

}  // namespace

ErrorScene stillCumulusScene(double voxelSize)
{
    SyntheticCumulusSettings c;
    c.seed = 3;
    c.voxelSize = voxelSize;
    c.baseHeight = 900.0;
    c.baseRadius = 700.0;
    c.towerHeight = 1.3;
    ErrorScene out;
    out.grid = rasterizeCumulus(cumulusBlobs(c), c);
    out.settings.camera.position = RenderVec3(400, -3800, 700);
    out.settings.camera.lookAt = RenderVec3(0, 0, 1200);
    out.settings.camera.fovDegrees = 40.0;
    out.settings.medium.extinction = 0.05;
    return out;
}

RenderVec3 sunAroundCamera(const RenderCamera& camera, const std::string& where)
{
    if (where != "front" && where != "beside" && where != "behind")
        throw std::invalid_argument("no sun '" + where + "': front, beside or behind");
    RenderVec3 f = camera.lookAt - camera.position;
    f = RenderVec3(f.x(), f.y(), 0.0).unitSafe();
    const RenderVec3 right(f.y(), -f.x(), 0.0);
    const RenderVec3 h = where == "front" ? f : where == "behind" ? -f : right;
    const double elevation = 35.0 * 3.14159265358979323846 / 180.0;
    return h * std::cos(elevation) + RenderVec3(0, 0, std::sin(elevation));
}

double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

LuminanceError luminanceError(const RenderedImage& image, const RenderedImage& reference)
{
    requireSameSize(image, reference);
    std::vector<std::pair<double, double>> refAndError;  // (L_ref, relative error)
    double sum = 0.0, sumRef = 0.0;
    for (std::size_t i = 0; i < reference.rgba.size() / 4; ++i) {
        if (reference.rgba[4 * i + 3] < kCloudAlpha) continue;
        const double lr = luminance(&reference.rgba[4 * i]), l = luminance(&image.rgba[4 * i]);
        if (!(lr > 0.0)) continue;
        refAndError.emplace_back(lr, std::abs(l - lr) / lr);
        sum += l;
        sumRef += lr;
    }
    LuminanceError e;
    e.pixels = refAndError.size();
    if (e.pixels == 0) return e;
    e.ratio = sum / sumRef;
    std::vector<double> errors;
    errors.reserve(refAndError.size());
    for (const auto& [l, err] : refAndError) errors.push_back(err);
    for (const double v : errors) e.mean += v / static_cast<double>(errors.size());
    std::nth_element(errors.begin(),
                     errors.begin() + static_cast<std::ptrdiff_t>(errors.size() * 9 / 10),
                     errors.end());
    e.p90 = errors[errors.size() * 9 / 10];
    std::sort(refAndError.begin(), refAndError.end());
    const std::size_t half = refAndError.size() / 2;
    for (std::size_t i = 0; i < refAndError.size(); ++i)
        (i < half ? e.darkMean : e.brightMean) += refAndError[i].second;
    e.darkMean /= static_cast<double>(std::max<std::size_t>(half, 1));
    e.brightMean /= static_cast<double>(std::max<std::size_t>(refAndError.size() - half, 1));
    return e;
}

double referenceNoise(const RenderedImage& a, const RenderedImage& b)
{
    requireSameSize(a, b);
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.rgba.size() / 4; ++i) {
        const double la = luminance(&a.rgba[4 * i]), lb = luminance(&b.rgba[4 * i]);
        const double alpha = 0.5 * (a.rgba[4 * i + 3] + b.rgba[4 * i + 3]);
        if (alpha < kCloudAlpha || !(la + lb > 0.0)) continue;
        sum += std::abs(la - lb) / (la + lb);
        ++n;
    }
    return n ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace cg::algo
