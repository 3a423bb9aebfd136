#include "ImageFiles.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <pybind11/stl/filesystem.h>

#include "Values.h"
#include "algo/render/image/Display.h"
#include "algo/render/image/OcioDisplay.h"
#include "nodes/data/Image.h"
#include "nodes/render/ImageFile.h"

namespace py = pybind11;

namespace cg::python {

void bindImageFiles(py::module_& m)
{
    m.def(
        "write_image",
        [](const std::filesystem::path& path, const py::handle& image, double exposure,
           const std::string& toneMap, bool dither, std::uint64_t seed) {
            // A bad array, tone curve or file name throws std::invalid_argument: a ValueError.
            if (!isImageFileName(path.string()))  // before the work, not after it
                throw std::invalid_argument(
                    "'" + path.string() + "' must end in .png (8-bit sRGB) or .exr (linear float)");
            const auto data =
                std::static_pointer_cast<const ImageData>(fromPython(image, "Image", "image"));
            algo::DisplaySettings display;
            display.exposure = exposure;
            if (toneMap == "ocio")  // $OCIO's config, else the built-in one, its defaults
                display.ocio = std::make_shared<algo::OcioDisplay>(algo::OcioChoice{});
            else
                display.curve = algo::toneCurveFromName(toneMap);
            display.dither = dither;
            display.seed = seed;
            py::gil_scoped_release release;
            writeImageFile(path, *data, display);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0, py::arg("tone_map") = "aces",
        py::arg("dither") = true, py::arg("seed") = 0,
        "Writes an image array (height, width, 3 or 4) of linear radiance as WriteImage does: "
        ".png through exposure, tone map (aces, hable, clamp, or ocio: OpenColorIO's display "
        "transform of $OCIO's config or the built-in one), sRGB and dither (seeded by "
        "`seed`, WriteImage's frame), .exr as linear float; atomically.");
}

}  // namespace cg::python
