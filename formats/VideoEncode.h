#pragma once
/// Numbered PNG frames to an H.264 MP4 through the ffmpeg program. No engine includes.

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

namespace cg::formats {

/// The encoder program could not be started (not installed, not on PATH, not executable).
class ProgramNotFound : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct VideoEncodeSettings {
    std::string program = "ffmpeg";  ///< a name looked up on PATH, or a path
    /// The frames: a file name in which the first run of '#' is the zero-padded frame number,
    /// e.g. /out/frames/cloud.####.png. Every frame firstFrame..lastFrame must exist.
    std::filesystem::path images;
    int firstFrame = 0;
    int lastFrame = 0;
    double fps = 24.0;  ///< frames per second of the video
    int crf = 18;       ///< x264 constant rate factor: 0 lossless .. 51 worst
};

/// Encodes the frames into an MP4 at `output` (H.264 via libx264, yuv420p so that every
/// player reads it; odd sizes are padded by a pixel). Runs the program with an argument
/// vector, never a shell. `poll` (optional) is called every few milliseconds while it runs
/// and may throw to stop it (the child is killed). Throws ProgramNotFound when the program
/// cannot be started, std::invalid_argument for bad settings or a missing frame (naming it),
/// std::runtime_error with the end of the program's log when it fails.
void encodeVideo(const VideoEncodeSettings& settings, const std::filesystem::path& output,
                 const std::function<void()>& poll = {});

}  // namespace cg::formats
