#pragma once
/// The cloud alone, for compositing: a renderer's beauty holds the cloud over what lies behind
/// it, beauty = cloud + (1 − alpha) background, with the cloud premultiplied by its alpha (the
/// convention of OpenEXR and of every compositor). Given the beauty and the background, the
/// cloud layer is what remains.

#include <vector>

namespace cg::algo {

/// The premultiplied cloud layer, 4 floats per pixel (RGBA, top row first): cloud.rgb =
/// beauty.rgb − (1 − alpha) background, evaluated in double and clamped at 0 (a negative
/// value can only be the beauty's rounding), cloud.a = alpha; 0 where alpha is 0 (nothing in
/// front of the background). `rgba` holds 4 floats per pixel, `background` 3 (linear RGB).
/// Throws std::invalid_argument if their pixel counts differ.
std::vector<float> cloudLayer(const std::vector<float>& rgba, const std::vector<float>& background);

}  // namespace cg::algo
