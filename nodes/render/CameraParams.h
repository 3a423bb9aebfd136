#pragma once
/// The Renderer's camera parameters: a static camera (cameraPosition, cameraLookAt, cameraUp,
/// fov), keys that move it (cameraKeys), or a Nuke .chan file (cameraFile), read into one
/// camera path.

#include <vector>

#include "algo/render/CameraPath.h"
#include "core/NodeDecl.h"
#include "core/Param.h"

namespace cg {

/// Numbers a key takes in cameraKeys: frame, position x y z, look-at x y z, field of view.
inline constexpr std::size_t kNumbersPerCameraKey = 8;

/// The keys the parameters give: the file's lines (each its own key; a line without a field
/// of view takes `fov`), else cameraKeys (each with cameraUp), else the static camera as one
/// key. Throws std::invalid_argument (formats::FormatError for the file) for unusable keys.
std::vector<algo::CameraKey> cameraKeysFrom(const ParamSet& params);

/// Checks cameraKeys and cameraFile at load, naming the parameter.
void checkCameraParams(const ParamSet& params, const ParamChecker& check);

/// The camera file's content into the key (the engine leaves input files out).
void hashCameraFile(const ParamSet& params, Hasher& hasher);

}  // namespace cg
