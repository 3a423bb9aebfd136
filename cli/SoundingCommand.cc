// cloudgraph sounding FILE: what a sounding file holds and what a parcel lifted from its
// ground does in it (LCL, LFC, EL, CAPE), so a user can check a file before a graph uses it.

#include <cmath>
#include <cstdio>
#include <string>

#include "algo/atmosphere/Parcel.h"
#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "formats/Sounding.h"
#include "nodes/atmosphere/SoundingProfile.h"

namespace cg::cli {

namespace {

/// "1185 m (1005 m above the ground)", or "none" for NaN.
std::string level(double z, double ground)
{
    if (std::isnan(z)) return "none";
    char text[96];
    std::snprintf(text, sizeof text, "%.0f m (%.0f m above the ground)", z, z - ground);
    return text;
}

}  // namespace

int soundingCommand(const Args& args)
{
    OptionParser opts(args);
    return guarded([&] {
        opts.parse();
        if (opts.positionals().size() != 1)
            throw InputError("command line", "usage: cloudgraph sounding FILE");
        const std::string& file = opts.positionals()[0];
        const formats::Sounding sounding = formats::readSounding(file);
        const algo::EnvironmentProfile profile = profileFromSounding(sounding);
        const double ground = profile.groundHeight();
        const algo::ParcelAscent a = algo::liftParcel(profile, ground);
        const formats::SoundingLevel& g = sounding.levels.front();

        std::printf("%s: %s sounding, %zu levels from %.0f m to %.0f m above sea level\n",
                    file.c_str(),
                    sounding.format == formats::SoundingFormat::Wyoming
                        ? "University of Wyoming text"
                        : "CSV",
                    sounding.levels.size(), ground, profile.topHeight());
        std::printf("  ground:  %.1f C, dew point %.1f C, %.1f hPa\n", g.temperatureC,
                    g.dewpointC, profile.pressure(ground));
        std::printf("  parcel lifted from the ground:\n");
        std::printf("  LCL:     %s, %.1f C\n", level(a.lclM, ground).c_str(), a.lclTemperatureC);
        std::printf("  LFC:     %s\n", level(a.lfcM, ground).c_str());
        std::printf("  EL:      %s\n", level(a.elM, ground).c_str());
        std::printf("  CAPE:    %.0f J/kg, CIN %.0f J/kg\n", a.capeJPerKg, a.cinJPerKg);
        return kExitOk;
    });
}

}  // namespace cg::cli
