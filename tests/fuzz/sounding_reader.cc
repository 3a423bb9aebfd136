// Fuzz target: the sounding reader (formats/Sounding.h), both formats. Every rejection must be
// a cg::formats::FormatError; a sounding that parses must hold what the reader promises: two
// levels or more, heights increasing, a ground dew point, every value finite or missing.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "formats/FormatError.h"
#include "formats/Sounding.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    cg::formats::Sounding s;
    try {
        s = cg::formats::parseSounding(std::string_view(reinterpret_cast<const char*>(data), size),
                                       "fuzz");
    } catch (const cg::formats::FormatError&) {
        return 0;
    }
    if (s.levels.size() < 2 || std::isnan(s.levels[0].dewpointC)) std::abort();
    for (std::size_t i = 0; i < s.levels.size(); ++i) {
        const cg::formats::SoundingLevel& l = s.levels[i];
        if (!std::isfinite(l.heightM) || !std::isfinite(l.temperatureC)) std::abort();
        if (i > 0 && !(l.heightM > s.levels[i - 1].heightM)) std::abort();
        if (std::isinf(l.dewpointC) || std::isinf(l.windSpeedMs)) std::abort();
    }
    return 0;
}
