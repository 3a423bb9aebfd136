#include "util/FramePattern.h"

namespace cg::util {

std::optional<HashRun> firstHashRun(const std::string& name)
{
    const auto first = name.find('#');
    if (first == std::string::npos) return std::nullopt;
    auto last = name.find_first_not_of('#', first);
    if (last == std::string::npos) last = name.size();
    return HashRun{first, last};
}

std::filesystem::path framePath(const std::filesystem::path& pattern, int frame)
{
    std::string name = pattern.filename().string();
    const auto run = firstHashRun(name);
    if (!run) return pattern;
    std::string digits = std::to_string(frame < 0 ? -frame : frame);
    if (digits.size() < run->width()) digits.insert(0, run->width() - digits.size(), '0');
    if (frame < 0) digits.insert(0, 1, '-');
    name.replace(run->first, run->width(), digits);
    return pattern.parent_path() / name;
}

std::string outputFileProblem(const std::string& path)
{
    if (path.empty()) return "the path is empty";
    if (path.back() == '/') return "'" + path + "' names a directory, not a file";
    const std::filesystem::path p(path);
    const std::string name = p.filename().string();
    if (name == "." || name == "..") return "'" + path + "' names a directory, not a file";
    if (p.parent_path().string().find('#') != std::string::npos)
        return "'" + path + "': #### (the frame number) may only be in the file name";
    if (const auto run = firstHashRun(name); run && run->width() > kMaxFrameDigits)
        return "'" + path + "' has a run of " + std::to_string(run->width()) + " '#'; at most " +
               std::to_string(kMaxFrameDigits) + " (frames have at most 7 digits)";
    return "";
}

}  // namespace cg::util
