#pragma once
/// Linear OpenEXR images: what compositors (Nuke, Houdini COPs, Blender) take from a renderer.

#include <string>
#include <vector>

namespace cg::formats {

/// Writes linear RGBA floats (4 per pixel, top row first) as a scanline OpenEXR file with
/// 32-bit float R, G, B, A channels and ZIP compression, exactly to `path`: the values are
/// stored unchanged (no exposure, no tone map). Throws std::runtime_error naming the file on
/// failure, std::invalid_argument if rgba.size() != 4 width height.
void writeExrRgba32(const std::string& path, int width, int height, const std::vector<float>& rgba);

struct ExrRgbaImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  ///< 4 floats per pixel, top row first
};

/// Reads R, G, B, A of an OpenEXR file as floats (a missing channel reads as 0, alpha as 1).
/// Throws std::runtime_error naming the file.
ExrRgbaImage readExrRgba(const std::string& path);

}  // namespace cg::formats
