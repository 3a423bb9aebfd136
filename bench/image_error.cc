// The luminance error of one rendered image against another (two OpenEXR files written by
// WriteImage): cloud pixels, the ratio of mean luminances, the mean and 90th percentile of
// |L - L_ref| / L_ref over the reference's cloud pixels (alpha >= 0.5), as algo::luminanceError
// measures the fast renderer against the path tracer. bench/run_figure_voxelize.py compares
// the voxelizer's kernels with it.
//
// Usage: image_error [--layer NAME] IMAGE.exr REFERENCE.exr
//   prints: pixels=N ratio=R mean=M p90=P differing=D max=X iou=I   exit 2 for an unreadable
//   file or other sizes; D counts the RGBA values that are not bit for bit the same, X is the
//   largest absolute difference among them (0 0: the images are identical); I is the
//   intersection over union of the two silhouettes (alpha >= 0.5). With --layer, a file that
//   has the layer NAME (WriteImage's `cloud`: the premultiplied cloud alone) is read from it,
//   so a render of the cloud over nothing (Blender's transparent film) compares with ours.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "algo/render/metrics/RenderError.h"
#include "formats/ExrFile.h"

namespace {

/// The file's RGBA, or its layer `layer`'s where it has one.
cg::algo::RenderedImage readImage(const std::string& path, const std::string& layer)
{
    cg::algo::RenderedImage image;
    if (!layer.empty()) {
        try {
            cg::formats::ExrChannelImage exr = cg::formats::readExrChannels(
                path, {layer + ".R", layer + ".G", layer + ".B", layer + ".A"});
            image.width = exr.width;
            image.height = exr.height;
            image.rgba = std::move(exr.values);
            return image;
        } catch (const std::runtime_error&) {  // no such layer: the main RGBA
        }
    }
    cg::formats::ExrRgbaImage exr = cg::formats::readExrRgba(path);
    image.width = exr.width;
    image.height = exr.height;
    image.rgba = std::move(exr.rgba);
    return image;
}

/// Intersection over union of the pixels with alpha >= 0.5 (1 when neither has any).
double silhouetteIou(const cg::algo::RenderedImage& a, const cg::algo::RenderedImage& b)
{
    std::size_t both = 0, either = 0;
    for (std::size_t i = 3; i < a.rgba.size(); i += 4) {
        const bool x = a.rgba[i] >= 0.5f, y = b.rgba[i] >= 0.5f;
        both += x && y;
        either += x || y;
    }
    return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

}  // namespace

int main(int argc, char** argv)
{
    const bool layered = argc == 5 && std::string(argv[1]) == "--layer";
    if (argc != 3 && !layered) {
        std::fprintf(stderr, "usage: image_error [--layer NAME] IMAGE.exr REFERENCE.exr\n");
        return 2;
    }
    const std::string layer = layered ? argv[2] : "";
    try {
        const cg::algo::RenderedImage image = readImage(argv[argc - 2], layer);
        const cg::algo::RenderedImage reference = readImage(argv[argc - 1], layer);
        const cg::algo::LuminanceError e = cg::algo::luminanceError(image, reference);
        std::size_t differing = 0;
        float most = 0.0f;
        for (std::size_t i = 0; i < image.rgba.size(); ++i) {
            if (std::memcmp(&image.rgba[i], &reference.rgba[i], sizeof(float)) == 0) continue;
            ++differing;
            most = std::max(most, std::fabs(image.rgba[i] - reference.rgba[i]));
        }
        std::printf("pixels=%zu ratio=%.5f mean=%.5f p90=%.5f differing=%zu max=%g iou=%.4f\n",
                    e.pixels, e.ratio, e.mean, e.p90, differing, double(most),
                    silhouetteIou(image, reference));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_error: %s\n", e.what());
        return 2;
    }
    return 0;
}
