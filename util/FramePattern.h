#pragma once
/// Frame-numbered file names: the first run of '#' in a file name is the zero-padded frame
/// ("cloud.####.png" at frame 42 is "cloud.0042.png"). The one implementation for writers,
/// readers and the video encoder.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace cg::util {

/// The longest run of '#' allowed: enough for any frame the graph format allows (1000000),
/// and refused above so that a long run can never truncate the number.
constexpr std::size_t kMaxFrameDigits = 9;

/// [first, last) of the first run of '#' in `name`, if any.
struct HashRun {
    std::size_t first = 0;
    std::size_t last = 0;
    std::size_t width() const { return last - first; }
};
std::optional<HashRun> firstHashRun(const std::string& name);

/// `pattern` with the first run of '#' in its file name replaced by `frame`, zero-padded to
/// the run's width (wider numbers keep all their digits); unchanged when there is no run.
std::filesystem::path framePath(const std::filesystem::path& pattern, int frame);

/// Why `path` cannot name a frame-numbered output file, or empty when it can: the file name
/// must not be empty, ".", "..", or end in '/', '#' may only appear in the file name, and
/// its first run may have at most kMaxFrameDigits characters.
std::string outputFileProblem(const std::string& path);

}  // namespace cg::util
