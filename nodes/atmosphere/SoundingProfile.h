#pragma once
/// A sounding file's levels as an environment profile: where the file format (formats/) meets
/// the atmosphere's algorithms (algo/), which may not include each other.

#include "algo/atmosphere/Profile.h"
#include "formats/Sounding.h"

namespace cg {

/// The profile of `sounding`: the same levels, with each wind turned from the direction it
/// blows from and its speed into east and north components (a wind from 270 degrees, the
/// west, blows toward the east). Throws std::invalid_argument as EnvironmentProfile does.
algo::EnvironmentProfile profileFromSounding(const formats::Sounding& sounding);

}  // namespace cg
