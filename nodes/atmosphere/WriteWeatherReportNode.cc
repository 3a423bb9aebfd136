// WriteWeatherReport: a meteorologist's view of a frame (docs/atmosphere.md): cloud base, top and
// fraction by height, the lifted parcel against the environment (a skew-T's data), LCL, LFC
// and EL, as JSON, CSV and a skew-T PNG with the cloud's extent.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <optional>
#include <stdexcept>

#include "algo/atmosphere/CloudColumn.h"
#include "algo/atmosphere/Convective.h"
#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/SkewT.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/PngFile.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/io/WriterSupport.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

/// A number for JSON: null when not finite.
std::string number(double v)
{
    if (!std::isfinite(v)) return "null";
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

/// A profile's convective condensation level and temperature, and the surface parcel heated
/// to it; none where the air is too dry to form cumulus by heating.
struct Convection {
    std::optional<algo::ConvectiveLevels> levels;
    std::optional<algo::ParcelAscent> thermal;
};

Convection convectionOf(const algo::EnvironmentProfile& profile)
{
    Convection c;
    try {
        c.levels = algo::convectiveLevels(profile);
    } catch (const std::invalid_argument&) {
        return c;
    }
    c.thermal = algo::liftParcel(profile, profile.groundHeight(), c.levels->convectiveTemperatureC,
                                 profile.dewpoint(profile.groundHeight()));
    return c;
}

/// What to tell a reader when no thermal from the ground rises freely to its LFC.
std::string freeConvectionWarning(const algo::ParcelAscent& parcel, const Convection& c)
{
    const algo::ParcelAscent& best = c.thermal ? *c.thermal : parcel;
    if (!std::isnan(best.lfcM)) return "";
    char text[200];
    std::snprintf(text, sizeof text,
                  "no parcel from the ground reaches a level of free convection (CIN %.0f J/kg "
                  "at the ground's temperature): clouds stay shallow or do not form",
                  parcel.cinJPerKg);
    return text;
}

struct Report {
    const algo::EnvironmentProfile& profile;
    const algo::ParcelAscent& parcel;
    const Convection& convection;
    const algo::CloudColumn& cloud;
    int frame;
    double time;
};

void writeJson(const std::filesystem::path& path, const Report& r)
{
    const double ground = r.profile.groundHeight();
    std::ofstream out(path);
    out << "{\n  \"frame\": " << r.frame << ",\n  \"time_s\": " << number(r.time)
        << ",\n  \"ground_m\": " << number(ground)
        << ",\n  \"condensed_particles\": " << r.cloud.condensed
        << ",\n  \"cloud_base_m\": " << number(ground + r.cloud.baseM)
        << ",\n  \"cloud_top_m\": " << number(ground + r.cloud.topM)
        << ",\n  \"lcl_m\": " << number(r.parcel.lclM)
        << ",\n  \"lfc_m\": " << number(r.parcel.lfcM) << ",\n  \"el_m\": " << number(r.parcel.elM)
        << ",\n  \"cape_j_per_kg\": " << number(r.parcel.capeJPerKg)
        << ",\n  \"cin_j_per_kg\": " << number(r.parcel.cinJPerKg) << ",\n  \"ccl_m\": "
        << number(r.convection.levels ? r.convection.levels->cclM : std::nan(""))
        << ",\n  \"convective_temperature_c\": "
        << number(r.convection.levels ? r.convection.levels->convectiveTemperatureC : std::nan(""))
        << ",\n  \"convective_lfc_m\": "
        << number(r.convection.thermal ? r.convection.thermal->lfcM : std::nan(""))
        << ",\n  \"warning\": \"" << freeConvectionWarning(r.parcel, r.convection) << "\""
        << ",\n  \"cloud_fraction\": {\"bin_m\": " << number(r.cloud.binM)
        << ", \"from_ground\": [";
    for (std::size_t k = 0; k < r.cloud.fraction.size(); ++k)
        out << (k ? ", " : "") << number(r.cloud.fraction[k]);
    out << "]},\n  \"parcel\": [";
    bool first = true;
    for (const algo::ParcelPoint& p : r.parcel.path) {
        if (std::fmod(p.heightM - ground, 100.0) > 1e-6 && &p != &r.parcel.path.back()) continue;
        out << (first ? "\n    " : ",\n    ") << "{\"height_m\": " << number(p.heightM)
            << ", \"pressure_hpa\": " << number(r.profile.pressure(p.heightM))
            << ", \"parcel_c\": " << number(p.parcelC)
            << ", \"environment_c\": " << number(p.environmentC)
            << ", \"dewpoint_c\": " << number(r.profile.dewpoint(p.heightM)) << "}";
        first = false;
    }
    out << "\n  ]\n}\n";
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

/// One row per cloud-fraction bin, at the bin's middle: what a plotting tool wants.
void writeCsv(const std::filesystem::path& path, const Report& r)
{
    const double ground = r.profile.groundHeight();
    std::ofstream out(path);
    out << "height_m,pressure_hPa,environment_C,dewpoint_C,parcel_C,cloud_fraction\n";
    const std::size_t rows =
        static_cast<std::size_t>((r.profile.topHeight() - ground) / r.cloud.binM);
    for (std::size_t k = 0; k < rows; ++k) {
        const double z = ground + (static_cast<double>(k) + 0.5) * r.cloud.binM;
        double parcel = std::nan("");
        for (const algo::ParcelPoint& p : r.parcel.path)
            if (p.heightM <= z) parcel = p.parcelC;
        out << number(z) << ',' << number(r.profile.pressure(z)) << ','
            << number(r.profile.temperature(z)) << ',' << number(r.profile.dewpoint(z)) << ','
            << (std::isfinite(parcel) ? number(parcel) : "") << ','
            << number(k < r.cloud.fraction.size() ? r.cloud.fraction[k] : 0.0) << '\n';
    }
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

class WriteWeatherReportNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto c = ctx.input<CondensationData>("condensation");
        const Atmosphere& atmosphere = ctx.input<AtmosphereData>("atmosphere")->atmosphere;
        const algo::EnvironmentProfile profile = environmentProfileOf(atmosphere);
        const algo::ParcelAscent parcel = algo::liftParcel(profile, profile.groundHeight());
        const Convection convection = convectionOf(profile);
        const VapourParticlesData& p = *c->particles;
        const algo::CloudColumn cloud = algo::cloudColumn(
            p.xs().data(), p.ys().data(), p.z.data(), c->condensedFrame.data(), p.size(),
            ctx.params().getFloat("heightBin"), ctx.params().getFloat("cellSize"));
        ctx.checkCancelled();
        const Report report{profile,     parcel,
                            convection,  cloud,
                            ctx.frame(), (ctx.frame() - ctx.startFrame()) * ctx.timeStep()};

        const std::filesystem::path base = ctx.outputPath("file");
        const auto withExtension = [&](const char* ext) {
            return std::filesystem::path(base.string() + ext);
        };
        // All three are written in full before any is committed.
        util::AtomicOutput json(withExtension(".json")), csv(withExtension(".csv")),
            png(withExtension(".png"));
        writeJson(json.tempPath(), report);
        writeCsv(csv.tempPath(), report);
        algo::SkewTOptions o;
        o.cloudBaseM = profile.groundHeight() + cloud.baseM;
        o.cloudTopM = profile.groundHeight() + cloud.topM;
        o.title = "Weather report, frame " + std::to_string(ctx.frame());
        const algo::SkewTImage image = algo::drawSkewT(profile, parcel, o);
        formats::writePngRgb8(png.tempPath().string(), image.width, image.height, image.rgb);
        ctx.checkCancelled();
        json.commit();
        csv.commit();
        png.commit();
        ctx.setOutput("files", std::make_shared<TextData>(json.target().string() + "\n" +
                                                          csv.target().string() + "\n" +
                                                          png.target().string()));
    }
};

}  // namespace

void registerWriteWeatherReportNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteWeatherReport",
        "Ours (docs/atmosphere.md): a meteorological report of the frame, three files named by "
        "'file' "
        "plus .json, .csv and .png. JSON: the cloud's base and top (lowest and highest "
        "condensation particle, metres above sea level), its cloud fraction by height (the "
        "share of the ground's cellSize cells, over the particles' bounding box, above which a "
        "condensation particle lies in each heightBin), and the parcel lifted from the "
        "ground: LCL, LFC, EL, CAPE, CIN and its temperature against the environment every "
        "100 m (the data of a skew-T diagram); the convective condensation level and "
        "temperature (ccl_m, convective_temperature_c) and the LFC of the surface parcel "
        "heated to it, and a warning when no parcel from the ground rises freely to an LFC "
        "(empty otherwise). CSV: one row per height bin with pressure, "
        "environment, dew point, parcel and cloud fraction. PNG: the skew-T log-p diagram "
        "(as `cloudgraph sounding --plot`) with the cloud's extent as a blue bar beside the "
        "LCL, LFC and EL ticks. The paper's Eq. 9 atmosphere is reported as a profile: its "
        "line to 20 km with the dew point T_dp, hydrostatic pressure from 1013.25 hPa.",
        port("condensation", "Condensation", "the particles and which have condensed"),
        "report/weather.####");
    d.category = "atmosphere";
    d.inputs.push_back(port("atmosphere", "Atmosphere", "the environment the cloud grew in"));
    d.outputs = {port("files", "Text", "the JSON, CSV and PNG paths, one per line")};
    d.params.push_back(floatParam("heightBin", 250.0, "m",
                                  "height of one cloud-fraction bin (value ours)", 1.0, 10000.0));
    d.params.push_back(floatParam("cellSize", 100.0, "m",
                                  "ground cell of the cloud fraction (value ours)", 1.0, 100000.0));
    d.create = [] { return std::make_unique<WriteWeatherReportNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
