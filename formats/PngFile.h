#pragma once
/// Minimal PNG file I/O over libpng, shared by the map and render image writers: non-interlaced
/// greyscale or RGB at 8 or 16 bits per sample, pixels passed through as PNG stores them (16-bit
/// samples big-endian, rows top first). Callers own the pixel encoding and orientation.

#include <cstdint>
#include <string>
#include <vector>

namespace cg::formats {

/// Writes a PNG exactly to `path` (never inferred from the extension). `rows` holds `height`
/// pointers, top row first, each to width * channels samples of bitDepth / 8 bytes; `channels`
/// is 1 (grey) or 3 (RGB), `bitDepth` 8 or 16. With `srgb` the file is tagged sRGB (with the
/// matching gAMA and cHRM). Throws std::invalid_argument on a bad size or format and
/// std::runtime_error naming the file on any I/O or libpng failure.
void writePng(const std::string& path, int width, int height, int channels, int bitDepth,
              const std::vector<const unsigned char*>& rows, bool srgb);

/// Pixels of a PNG as stored: rows top first, tightly packed, 16-bit samples big-endian.
struct PngPixels {
    int width = 0;
    int height = 0;
    int channels = 0;
    int bitDepth = 0;
    std::vector<unsigned char> bytes;  ///< height * width * channels * bitDepth / 8 bytes
};

/// Reads a PNG that must be stored as exactly `channels` (1 grey, 3 RGB; palette and alpha
/// types are refused) at `bitDepth` bits, with no conversions, and at most `maxSide` pixels
/// on either side. Throws std::runtime_error naming the file if it cannot be opened, is not
/// a PNG ("not a PNG file"), is stored in another format ("not a 16-bit greyscale PNG",
/// "not an 8-bit RGB PNG", ...; checked before any pixel is read) or is malformed, truncated
/// or too large ("PNG read failed: <libpng's reason>"); std::invalid_argument if `channels`
/// or `bitDepth` is not one of the values above. `channels` 0 takes grey or RGB and
/// `bitDepth` 0 takes 8 or 16 bits, as stored (the result says which).
PngPixels readPng(const std::string& path, int channels, int bitDepth, std::uint32_t maxSide);

/// Writes an 8-bit RGB PNG (top row first) tagged sRGB, exactly to `path`. Throws
/// std::runtime_error naming the file on failure, std::invalid_argument on bad sizes.
void writePngRgb8(const std::string& path, int width, int height,
                  const std::vector<std::uint8_t>& rgb);

/// The same PNG as bytes in memory (a preview served over HTTP).
std::string encodePngRgb8(int width, int height, const std::vector<std::uint8_t>& rgb);

struct Rgb8Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< 3 bytes per pixel, top row first
};

/// Reads an 8-bit RGB PNG (tests and tools). Throws std::runtime_error for anything else.
Rgb8Image readPngRgb8(const std::string& path);

}  // namespace cg::formats
