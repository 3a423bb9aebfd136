#include "ImageFiles.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <pybind11/stl/filesystem.h>

#include "Values.h"
#include "algo/render/Display.h"
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
            if (!isImageFileName(path.string()))
                throw py::value_error("'" + path.string() +
                                      "' must end in .png (8-bit sRGB) or .exr (linear float)");
            if (toneMap != "aces" && toneMap != "hable" && toneMap != "clamp")
                throw py::value_error("tone_map '" + toneMap + "' is not aces, hable or clamp");
            std::shared_ptr<const ImageData> data;
            try {
                data =
                    std::static_pointer_cast<const ImageData>(fromPython(image, "Image", "image"));
            } catch (const std::runtime_error& e) {
                throw py::value_error(e.what());
            }
            algo::DisplaySettings display;
            display.exposure = exposure;
            display.curve = algo::toneCurveFromName(toneMap);
            display.dither = dither;
            display.seed = seed;
            py::gil_scoped_release release;
            writeImageFile(path, *data, display);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0, py::arg("tone_map") = "aces",
        py::arg("dither") = true, py::arg("seed") = 0,
        "Writes an image array (height, width, 3 or 4) of linear radiance as WriteImage does: "
        ".png through exposure, tone map (aces, hable, clamp), sRGB and dither (seeded by "
        "`seed`, WriteImage's frame), .exr as linear float; atomically.");
}

}  // namespace cg::python
