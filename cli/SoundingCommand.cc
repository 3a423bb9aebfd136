// cloudgraph sounding FILE [--plot PNG]: what a sounding file holds and what a parcel lifted
// from its ground does in it (LCL, LFC, EL, CAPE), and its skew-T diagram, so a user can check
// a file before a graph uses it.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "algo/atmosphere/Convective.h"
#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/SkewT.h"
#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "formats/PngFile.h"
#include "formats/Sounding.h"
#include "nodes/atmosphere/SoundingProfile.h"
#include "util/AtomicFile.h"

namespace cg::cli {

namespace {

/// "1185 m (1005 m above the ground), 881 hPa", or "none" for NaN.
std::string level(double z, const algo::EnvironmentProfile& profile)
{
    if (std::isnan(z)) return "none";
    char text[128];
    std::snprintf(text, sizeof text, "%.0f m (%.0f m above the ground), %.0f hPa", z,
                  z - profile.groundHeight(), profile.pressure(z));
    return text;
}

}  // namespace

int soundingCommand(const Args& args)
{
    OptionParser opts(args, "sounding");
    return guarded([&] {
        opts.parse();
        if (opts.positionals().size() != 1)
            throw InputError("command line", "usage: cloudgraph sounding FILE [--plot PNG]");
        const std::string& file = opts.positionals()[0];
        const formats::Sounding sounding = formats::readSounding(file);
        const algo::EnvironmentProfile profile = profileFromSounding(sounding);
        const double ground = profile.groundHeight();
        const algo::ParcelAscent a = algo::liftParcel(profile, ground);
        const formats::SoundingLevel& g = sounding.levels.front();

        std::printf(
            "%s: %s sounding, %zu levels from %.0f m to %.0f m above sea level\n", file.c_str(),
            sounding.format == formats::SoundingFormat::Wyoming ? "University of Wyoming text"
                                                                : "CSV",
            sounding.levels.size(), ground, profile.topHeight());
        std::printf("  ground:  %.1f C, dew point %.1f C, %.1f hPa\n", g.temperatureC, g.dewpointC,
                    profile.pressure(ground));
        std::printf("  parcel lifted from the ground:\n");
        std::printf("  LCL:     %s, %.1f C\n", level(a.lclM, profile).c_str(), a.lclTemperatureC);
        std::printf("  LFC:     %s\n", level(a.lfcM, profile).c_str());
        std::printf("  EL:      %s\n", level(a.elM, profile).c_str());
        std::printf("  CAPE:    %.0f J/kg, CIN %.0f J/kg\n", a.capeJPerKg, a.cinJPerKg);
        try {
            const algo::ConvectiveLevels c = algo::convectiveLevels(profile);
            std::printf("  CCL:     %s, convective temperature %.1f C\n",
                        level(c.cclM, profile).c_str(), c.convectiveTemperatureC);
        } catch (const std::invalid_argument&) {
            std::printf("  CCL:     none (the surface mixing ratio never saturates)\n");
        }
        if (const auto plot = opts.value("--plot")) {
            algo::SkewTOptions o;
            o.title = std::filesystem::path(file).filename().string();
            const algo::SkewTImage image = algo::drawSkewT(profile, a, o);
            util::AtomicOutput out(*plot);  // whole or not at all
            formats::writePngRgb8(out.tempPath().string(), image.width, image.height, image.rgb);
            out.commit();
            std::printf("  skew-T:  %s\n", plot->c_str());
        }
        return kExitOk;
    });
}

}  // namespace cg::cli
