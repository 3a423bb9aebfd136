#include "formats/VideoEncode.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>
#include <vector>

#include "util/FramePattern.h"

extern char** environ;

namespace cg::formats {

namespace {

namespace fs = std::filesystem;

/// The first run of '#' in the file name; throws when there is none.
util::HashRun hashRun(const std::string& name)
{
    const auto run = util::firstHashRun(name);
    if (!run) throw std::invalid_argument("image pattern '" + name + "' has no #### frame number");
    return *run;
}

/// The pattern in ffmpeg's image2 syntax: %0Nd for the #### run, '%' escaped as "%%".
std::string ffmpegPattern(const fs::path& pattern)
{
    const std::string name = pattern.filename().string();
    const auto [first, last] = hashRun(name);
    std::string out;
    for (std::size_t i = 0; i < name.size(); ++i) {
        if (i == first) {
            out += "%0" + std::to_string(last - first) + "d";
            i = last - 1;
        } else {
            out += name[i] == '%' ? std::string("%%") : std::string(1, name[i]);
        }
    }
    return (pattern.parent_path() / out).string();
}

std::string tail(const fs::path& log, std::size_t chars)
{
    std::ifstream in(log, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text.size() > chars ? "..." + text.substr(text.size() - chars) : text;
}

/// Removes a file on scope exit.
struct FileGuard {
    fs::path path;
    ~FileGuard()
    {
        std::error_code ec;
        fs::remove(path, ec);
    }
};

std::string number(double v)
{
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

}  // namespace

void encodeVideo(const VideoEncodeSettings& s, const fs::path& output,
                 const std::function<void()>& poll)
{
    if (!(s.fps > 0.0) || !std::isfinite(s.fps)) throw std::invalid_argument("fps must be > 0");
    if (s.crf < 0 || s.crf > 51) throw std::invalid_argument("crf must be in 0..51");
    if (s.lastFrame < s.firstFrame)
        throw std::invalid_argument("last frame " + std::to_string(s.lastFrame) +
                                    " is before the first frame " + std::to_string(s.firstFrame));
    if (s.program.empty()) throw std::invalid_argument("the encoder program name is empty");
    if (s.images.parent_path().string().find('#') != std::string::npos)
        throw std::invalid_argument("image pattern '" + s.images.string() +
                                    "': #### must be in the file name, not a directory");
    hashRun(s.images.filename().string());
    // ffmpeg stops at the first gap in the numbering: find it here and name it.
    for (int f = s.firstFrame; f <= s.lastFrame; ++f) {
        const fs::path p = util::framePath(s.images, f);
        if (!fs::is_regular_file(p))
            throw std::invalid_argument("frame " + std::to_string(f) +
                                        " is missing: " + p.string());
    }

    const FileGuard log{fs::path(output.string() + ".ffmpeg.log")};
    const std::vector<std::string> argv = {
        s.program, "-nostdin", "-hide_banner", "-loglevel", "error", "-y", "-framerate",
        number(s.fps), "-start_number", std::to_string(s.firstFrame), "-i", ffmpegPattern(s.images),
        "-frames:v", std::to_string(s.lastFrame - s.firstFrame + 1),
        // yuv420p halves the chroma resolution, so both sizes must be even. The frames are
        // sRGB: converted to YUV with Rec.709's matrix (ffmpeg's default is Rec.601's) in video
        // range, and tagged so (primaries and matrix bt709, transfer the sRGB curve), so a
        // colour-managed player shows the PNGs' colours.
        "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2,scale=out_color_matrix=bt709:out_range=tv", "-c:v",
        "libx264", "-pix_fmt", "yuv420p", "-color_primaries", "bt709", "-colorspace", "bt709",
        "-color_trc", "iec61966-2-1", "-color_range", "tv", "-crf", std::to_string(s.crf),
        "-movflags", "+faststart", "-f", "mp4", output.string()};
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = -1;
    // posix_spawnp searches PATH like execvp; glibc reports a failed exec as its result.
    const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw ProgramNotFound("cannot run '" + s.program + "': " + std::strerror(rc));

    int status = 0;
    for (;;) {
        const pid_t r = ::waitpid(pid, &status, WNOHANG);
        if (r == pid) break;
        if (r < 0 && errno != EINTR) throw std::runtime_error("waitpid failed for " + s.program);
        if (poll) {
            try {
                poll();
            } catch (...) {
                ::kill(pid, SIGKILL);
                ::waitpid(pid, &status, 0);
                throw;
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    // A spawn that exec'd nothing exits 127 on some C libraries instead of failing above.
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127 && fs::file_size(log.path) == 0)
        throw ProgramNotFound("cannot run '" + s.program + "'");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error(s.program + " failed (" +
                                 (WIFEXITED(status)
                                      ? "exit status " + std::to_string(WEXITSTATUS(status))
                                      : "killed by signal " + std::to_string(WTERMSIG(status))) +
                                 "): " + tail(log.path, 800));
}

}  // namespace cg::formats
