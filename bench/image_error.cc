// The luminance error of one rendered image against another (two OpenEXR files written by
// WriteImage): cloud pixels, the ratio of mean luminances, the mean and 90th percentile of
// |L - L_ref| / L_ref over the reference's cloud pixels (alpha >= 0.5), as algo::luminanceError
// measures the fast renderer against the path tracer. bench/run_figure_voxelize.py compares
// the voxelizer's kernels with it.
//
// Usage: image_error IMAGE.exr REFERENCE.exr
//   prints: pixels=N ratio=R mean=M p90=P differing=D max=X   exit 2 for an unreadable file
//   or other sizes; D counts the RGBA values that are not bit for bit the same, X is the
//   largest absolute difference among them (0 0: the images are identical).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "algo/render/metrics/RenderError.h"
#include "formats/ExrFile.h"

namespace {

cg::algo::RenderedImage readImage(const std::string& path)
{
    cg::formats::ExrRgbaImage exr = cg::formats::readExrRgba(path);
    cg::algo::RenderedImage image;
    image.width = exr.width;
    image.height = exr.height;
    image.rgba = std::move(exr.rgba);
    return image;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: image_error IMAGE.exr REFERENCE.exr\n");
        return 2;
    }
    try {
        const cg::algo::RenderedImage image = readImage(argv[1]);
        const cg::algo::RenderedImage reference = readImage(argv[2]);
        const cg::algo::LuminanceError e = cg::algo::luminanceError(image, reference);
        std::size_t differing = 0;
        float most = 0.0f;
        for (std::size_t i = 0; i < image.rgba.size(); ++i) {
            if (std::memcmp(&image.rgba[i], &reference.rgba[i], sizeof(float)) == 0) continue;
            ++differing;
            most = std::max(most, std::fabs(image.rgba[i] - reference.rgba[i]));
        }
        std::printf("pixels=%zu ratio=%.5f mean=%.5f p90=%.5f differing=%zu max=%g\n", e.pixels,
                    e.ratio, e.mean, e.p90, differing, double(most));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_error: %s\n", e.what());
        return 2;
    }
    return 0;
}
