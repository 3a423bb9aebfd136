#include "formats/ChanFile.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <system_error>

#include "formats/FormatError.h"
#include "util/InputFile.h"

namespace cg::formats {

namespace {

constexpr double kMaxFrame = 1e9;
constexpr double kMaxRotation = 1e6;

/// The whitespace-separated fields of one line.
std::vector<std::string_view> fields(std::string_view line)
{
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

class LineParser {
public:
    LineParser(const std::string& name, std::size_t number) : mName(name), mNumber(number) {}

    [[noreturn]] void fail(const std::string& message) const
    {
        throw FormatError(mName + ":" + std::to_string(mNumber), message);
    }

    double number(std::string_view field, const char* what) const
    {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (ec != std::errc() || end != field.data() + field.size())
            fail(std::string(what) + " '" + std::string(field.substr(0, 40)) + "' is not a number");
        if (!std::isfinite(v)) fail(std::string(what) + " is not finite");
        return v;
    }

    ChanLine line(const std::vector<std::string_view>& f) const
    {
        if (f.size() != 7 && f.size() != 8)
            fail(
                "a camera line holds 7 or 8 numbers (frame, translate x y z, rotate x y z, "
                "vertical field of view), not " +
                std::to_string(f.size()));
        ChanLine l;
        const double frame = number(f[0], "the frame");
        if (frame != std::floor(frame) || std::abs(frame) > kMaxFrame)
            fail("the frame must be a whole number within +-10^9");
        l.frame = static_cast<std::int64_t>(frame);
        static const char* const kNames[6] = {"translate x", "translate y", "translate z",
                                              "rotate x",    "rotate y",    "rotate z"};
        for (int a = 0; a < 3; ++a) {
            l.translate[a] = number(f[1 + a], kNames[a]);
            l.rotateDegrees[a] = number(f[4 + a], kNames[3 + a]);
            if (std::abs(l.rotateDegrees[a]) > kMaxRotation)
                fail(std::string(kNames[3 + a]) + " is beyond +-10^6 degrees");
        }
        if (f.size() == 8) {
            l.verticalFovDegrees = number(f[7], "the field of view");
            if (!(l.verticalFovDegrees > 0.0 && l.verticalFovDegrees < 180.0))
                fail("the field of view must be in (0, 180) degrees");
        }
        return l;
    }

private:
    const std::string& mName;
    std::size_t mNumber;
};

void appendNumber(std::string& out, double v)
{
    if (v == 0.0) v = 0.0;  // "0", never "-0"
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.append(buffer, ec == std::errc() ? end : buffer);
}

}  // namespace

std::vector<ChanLine> parseChan(std::string_view text, const std::string& name)
{
    std::vector<ChanLine> lines;
    std::size_t number = 0, at = 0;
    while (at < text.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view raw = text.substr(at, end - at);
        at = end + 1;
        ++number;
        const std::vector<std::string_view> f = fields(raw);
        if (f.empty() || f[0].front() == '#') continue;
        const LineParser parser(name, number);
        ChanLine l = parser.line(f);
        if (!lines.empty() && !(l.frame > lines.back().frame))
            parser.fail("frame " + std::to_string(l.frame) +
                        " does not come after the line before (frame " +
                        std::to_string(lines.back().frame) + ")");
        lines.push_back(l);
    }
    if (lines.empty()) throw FormatError(name, "no camera lines (frame tx ty tz rx ry rz [fov])");
    return lines;
}

std::vector<ChanLine> readChan(const std::filesystem::path& path)
{
    if (const std::string problem = util::inputFileProblem(path, kMaxChanBytes); !problem.empty())
        throw FormatError(path.string(), "cannot read the camera file: it " + problem);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FormatError(path.string(), "cannot open the camera file");
    // One byte more than its checked size, so a file that grew since is seen, not read whole.
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw FormatError(path.string(), "cannot read the camera file: " + ec.message());
    std::string text(static_cast<std::size_t>(size) + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad()) throw FormatError(path.string(), "cannot read the camera file");
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > size)
        throw FormatError(path.string(), "cannot read the camera file: it changed while read");
    return parseChan(text, path.string());
}

std::string chanText(const std::vector<ChanLine>& lines)
{
    std::string out;
    for (const ChanLine& l : lines) {
        out += std::to_string(l.frame);
        for (double v : {l.translate[0], l.translate[1], l.translate[2], l.rotateDegrees[0],
                         l.rotateDegrees[1], l.rotateDegrees[2]}) {
            out += ' ';
            appendNumber(out, v);
        }
        if (l.verticalFovDegrees != 0.0) {  // 0: the line had none
            out += ' ';
            appendNumber(out, l.verticalFovDegrees);
        }
        out += '\n';
    }
    return out;
}

}  // namespace cg::formats
