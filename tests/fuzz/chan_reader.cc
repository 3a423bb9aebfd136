// Fuzz target: the Nuke .chan camera reader (formats/ChanFile.h). Every rejection must be a
// cg::formats::FormatError; a file that parses must hold what the reader promises (at least
// one line, frames increasing, values finite, the field of view in (0, 180) or absent), and
// write back to text that parses to the same lines.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "formats/ChanFile.h"
#include "formats/FormatError.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::vector<cg::formats::ChanLine> lines;
    try {
        lines = cg::formats::parseChan(std::string_view(reinterpret_cast<const char*>(data), size),
                                       "fuzz");
    } catch (const cg::formats::FormatError&) {
        return 0;
    }
    if (lines.empty()) std::abort();
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const cg::formats::ChanLine& l = lines[i];
        if (i > 0 && !(l.frame > lines[i - 1].frame)) std::abort();
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(l.translate[a]) || !std::isfinite(l.rotateDegrees[a])) std::abort();
        if (l.verticalFovDegrees != 0.0 &&
            !(l.verticalFovDegrees > 0.0 && l.verticalFovDegrees < 180.0))
            std::abort();
    }
    const std::vector<cg::formats::ChanLine> again =
        cg::formats::parseChan(cg::formats::chanText(lines), "again");
    if (again.size() != lines.size()) std::abort();
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (again[i].frame != lines[i].frame ||
            again[i].verticalFovDegrees != lines[i].verticalFovDegrees ||
            again[i].translate[1] != lines[i].translate[1])
            std::abort();
    return 0;
}
