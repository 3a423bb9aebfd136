// The luminance error of one rendered image against another (two OpenEXR files written by
// WriteImage): cloud pixels, the ratio of mean luminances, the mean and 90th percentile of
// |L - L_ref| / L_ref over the reference's cloud pixels (alpha >= 0.5), as algo::luminanceError
// measures the fast renderer against the path tracer. bench/run_figure_voxelize.py compares
// the voxelizer's kernels with it.
//
// Usage: image_error IMAGE.exr REFERENCE.exr
//   prints: pixels=N ratio=R mean=M p90=P      exit 2 for an unreadable file or other sizes

#include <cstdio>
#include <exception>
#include <string>

#include "algo/render/RenderError.h"
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
        const cg::algo::LuminanceError e = cg::algo::luminanceError(readImage(argv[1]), readImage(argv[2]));
        std::printf("pixels=%zu ratio=%.5f mean=%.5f p90=%.5f\n", e.pixels, e.ratio, e.mean, e.p90);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_error: %s\n", e.what());
        return 2;
    }
    return 0;
}
