#pragma once
/// Linear OpenEXR images: what compositors (Nuke, Houdini COPs, Blender) take from a renderer.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cg::formats {

/// Writes linear RGBA floats (4 per pixel, top row first) as a scanline OpenEXR file with
/// 32-bit float R, G, B, A channels and ZIP compression, exactly to `path`: the values are
/// stored unchanged (no exposure, no tone map). Throws std::runtime_error naming the file on
/// failure, std::invalid_argument if rgba.size() != 4 width height.
void writeExrRgba32(const std::string& path, int width, int height, const std::vector<float>& rgba);

/// Interleaved float pixels and the names of their channels as the file stores them:
/// channels.size() floats per pixel, top row first, channel c of pixel i at
/// values[i * channels.size() + c]. A layer's channels are named "layer.channel" (OpenEXR's
/// convention, which Nuke and Blender read as layers): {"cloud.R", "cloud.G", ...}.
struct ExrPixels {
    std::vector<std::string> channels;
    const std::vector<float>& values;
};

/// A 4 x 4 matrix as OpenEXR stores it (Imath's M44f, row-major, for row vectors p' = p M).
using ExrMatrix = std::array<std::array<float, 4>, 4>;

/// The standard attributes of a rendered image's camera (OpenEXR's worldToCamera and
/// worldToNDC), which Nuke and other compositors read to rebuild it.
struct ExrCamera {
    ExrMatrix worldToCamera{};
    ExrMatrix worldToNDC{};
};

/// Writes every channel of every `parts` entry as 32-bit float into one scanline OpenEXR file
/// with ZIP compression, exactly to `path`, values unchanged, with the camera's attributes
/// when given and the chromaticities of linear Rec.709 (sRGB primaries, D65 white). {{{"R", "G",
/// "B", "A"}, rgba}} is writeExrRgba32's file. Throws std::invalid_argument if a part's values do
/// not hold channels.size() floats per pixel, if a part has no channel or a name repeats;
/// std::runtime_error naming the file on failure.
void writeExrFloat32(const std::string& path, int width, int height,
                     const std::vector<ExrPixels>& parts,
                     const std::optional<ExrCamera>& camera = std::nullopt);

/// The file's worldToCamera and worldToNDC attributes, if it has both. Throws
/// std::runtime_error naming the file.
std::optional<ExrCamera> readExrCamera(const std::string& path);

/// CIE xy of the red, green and blue primaries and of the white point, in that order.
using ExrChromaticities = std::array<float, 8>;

/// The file's chromaticities attribute, if it has one. Throws std::runtime_error naming the
/// file.
std::optional<ExrChromaticities> readExrChromaticities(const std::string& path);

struct ExrRgbaImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  ///< 4 floats per pixel, top row first
};

/// Reads R, G, B, A of an OpenEXR file as floats (a missing channel reads as 0, alpha as 1).
/// Throws std::runtime_error naming the file.
ExrRgbaImage readExrRgba(const std::string& path);

/// Named channels of an OpenEXR file read as floats.
struct ExrChannelImage {
    int width = 0;
    int height = 0;
    std::vector<std::string> channels;  ///< those asked for, in that order
    std::vector<float> values;          ///< channels.size() floats per pixel, top row first
};

/// Reads the named channels of an OpenEXR file (e.g. {"cloud.R", "cloud.A"}) as floats,
/// interleaved in the order asked. Throws std::runtime_error naming the file and the channel
/// if one is missing, or naming the file on any other failure.
ExrChannelImage readExrChannels(const std::string& path, const std::vector<std::string>& channels);

/// A single-channel image of an OpenEXR file: its "Y" channel if it has one, else the Rec. 709
/// luminance of R, G and B (a missing one reads as 0), rows top first. Refuses a file with
/// more than `maxPixels` pixels before reading them, and one with none of Y, R, G, B. Throws
/// std::runtime_error naming the file.
ExrChannelImage readExrLuminance(const std::string& path, std::uint64_t maxPixels);

/// The names of every channel in an OpenEXR file, in the file's (alphabetical) order.
/// Throws std::runtime_error naming the file.
std::vector<std::string> exrChannelNames(const std::string& path);

}  // namespace cg::formats
