// Voxelizer: cloud particles to an OpenVDB fog volume (Sec. 6.3).

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "algo/volume/DomainWarp.h"
#include "algo/volume/FloretDetail.h"
#include "algo/volume/GaussianSplat.h"
#include "algo/volume/SurfaceDetail.h"
#include "algo/volume/Voxelize.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/volume/CloudWaterSetup.h"
#include "nodes/volume/VolumeNodes.h"
#include "util/SystemMemory.h"

namespace cg {

namespace {

/// The detail warped, grown and eroded on the splats, all riding with the copies.
struct DetailSettings {
    algo::DomainWarpSettings warp;
    algo::FloretSettings florets;
    algo::SurfaceDetailSettings erosion;
    bool eroding() const { return erosion.amplitude > 0.0; }
    /// The warp and the florets read the copies' territories.
    bool growing() const { return florets.radius > 0.0 || warp.amplitude > 0.0; }
};

/// A voxelized frame, how many particles went into it, and where its copies are: their
/// origins as a field for the erosion and their territories for the florets (each empty
/// unless that detail is on, and for particles without copies: vapour, primitive frames).
struct Voxelized {
    openvdb::FloatGrid::Ptr grid;
    std::uint64_t count = 0;
    std::optional<algo::CopyOriginField> origins;
    std::optional<algo::CopyTerritory> territory;

    /// Empty copy records for the detail that is on, to add particles to.
    void expectCopies(const algo::VoxelizeSettings& s, const DetailSettings& detail)
    {
        const double cell = algo::copyOriginCellSize(s.radius, s.voxelSize);
        if (detail.eroding()) origins.emplace(cell);
        if (detail.growing()) territory.emplace(cell);
    }
    void addCopies(const float* xyz, const std::uint32_t* sources, std::size_t n,
                   const float* copyOrigins, std::size_t copyCount)
    {
        if (copyCount == 0) return;
        if (origins) origins->add(xyz, sources, n, copyOrigins, copyCount);
        if (territory) territory->add(xyz, sources, n, copyOrigins, copyCount);
    }
    void finishCopies()
    {
        if (origins) origins->finish();
        if (territory) territory->finish();
    }
};

/// The gaussian splat and the copy records fed chunk by chunk as the particles stream
/// (nothing frame-sized when they come from GenerateCloud).
Voxelized splatStreaming(const CloudParticlesData& particles, const algo::VoxelizeSettings& s,
                         const DetailSettings& detail, CookContext& ctx)
{
    algo::GaussianSplatter splatter(s);
    Voxelized out;
    out.expectCopies(s, detail);
    particles.forEachChunk(
        [&](const algo::CloudChunk& chunk) {
            splatter.add(chunk.positions, chunk.count);
            out.addCopies(chunk.positions, chunk.sources, chunk.count, chunk.copyOrigins,
                          chunk.copyCount);
        },
        CloudChunkFields{false, detail.eroding() || detail.growing()},
        [&] { ctx.checkCancelled(); });
    out.count = splatter.count();
    out.grid = splatter.finish([&] { ctx.checkCancelled(); });
    out.finishCopies();
    return out;
}

/// The smooth and sphere kernels sum in a fixed order: they splat the frame's arrays.
Voxelized splatArrays(const CloudParticlesData& particles, const algo::VoxelizeSettings& s,
                      const DetailSettings& detail, CookContext& ctx)
{
    const auto& a = particles.arrays([&] { ctx.checkCancelled(); });
    Voxelized out;
    out.count = particles.size();
    out.grid =
        algo::voxelizeParticles(a.positions.data(), out.count, s, [&] { ctx.checkCancelled(); });
    out.expectCopies(s, detail);
    out.addCopies(a.positions.data(), a.sources.data(), out.count, a.copyOrigins.data(),
                  a.copyOrigins.size() / 3);
    out.finishCopies();
    return out;
}

/// The envelope warped, florets grown on it, then its soft edge eroded, all in the copies'
/// own coordinates, or in world coordinates where the particles have no copies.
void addDetail(Voxelized& v, const DetailSettings& detail, CookContext& ctx)
{
    const auto cancelled = [&] { ctx.checkCancelled(); };
    const bool territories = v.territory && !v.territory->empty();
    algo::warpVolume(*v.grid, territories ? &*v.territory : nullptr, detail.warp, cancelled);
    algo::growFlorets(*v.grid, detail.florets, territories ? &*v.territory : nullptr, cancelled);
    const bool copies = v.origins && v.origins->cellCount() > 0;
    algo::erodeSurface(*v.grid, copies ? &*v.origins : nullptr, detail.erosion, cancelled);
}

/// The detail the parameters ask for; the erosion's frequency is per particle radius.
DetailSettings detailFrom(const ParamSet& p, double radius)
{
    DetailSettings d;
    d.erosion.amplitude = p.getFloat("detailAmplitude");
    d.erosion.frequency = p.getFloat("detailFrequency") / radius;
    d.erosion.octaves = static_cast<int>(p.getInt("detailOctaves"));
    d.warp.amplitude = p.getFloat("warpAmplitude");
    d.warp.wavelength = p.getFloat("warpWavelength");
    d.warp.octaves = static_cast<int>(p.getInt("warpOctaves"));
    d.warp.roughness = p.getFloat("warpRoughness");
    d.florets.radius = p.getFloat("floretRadius");
    d.florets.levels = static_cast<int>(p.getInt("floretLevels"));
    d.florets.children = static_cast<int>(p.getInt("floretChildren"));
    return d;
}

class VoxelizerNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto particles = ctx.input<CloudParticlesData>("particles");
        const ParamSet& p = ctx.params();
        algo::VoxelizeSettings s;
        s.voxelSize = p.getFloat("voxelSize");
        s.radius = p.getFloat("radius");
        s.kernel = algo::voxelKernelFromName(p.getString("kernel"));
        s.density = p.getFloat("density");
        s.clamp = p.getBool("clamp");
        s.maxBytes = util::nodeAllocationLimitBytes();

        const DetailSettings detail = detailFrom(p, s.radius);
        Voxelized voxelized;
        try {
            if (detail.florets.radius > 0.0) algo::checkFloretSettings(detail.florets);
            voxelized = s.kernel == algo::VoxelKernel::Gaussian
                            ? splatStreaming(*particles, s, detail, ctx)
                            : splatArrays(*particles, s, detail, ctx);
            addDetail(voxelized, detail, ctx);
        } catch (const algo::VoxelizeTooLarge& e) {
            throw InputError(ctx.nodeId() + "/params/voxelSize", e.what());
        }
        openvdb::FloatGrid& grid = *voxelized.grid;
        algo::filterVolume(grid, algo::voxelFilterFromName(p.getString("filter")),
                           static_cast<int>(p.getInt("filterWidth")),
                           static_cast<int>(p.getInt("filterIterations")));
        shapeBaseAndWater(grid, ctx);

        // Provenance for whoever opens the file (vdb_print, Houdini, Blender).
        grid.insertMeta("frame", openvdb::Int32Metadata(ctx.frame()));
        grid.insertMeta("units", openvdb::StringMetadata("metres"));
        grid.insertMeta("voxel_size_m", openvdb::DoubleMetadata(s.voxelSize));
        grid.insertMeta("particle_radius_m", openvdb::DoubleMetadata(s.radius));
        grid.insertMeta("kernel", openvdb::StringMetadata(p.getString("kernel")));
        grid.insertMeta("particle_count",
                        openvdb::Int64Metadata(static_cast<openvdb::Int64>(voxelized.count)));
        ctx.setOutput("volume", std::make_shared<FogVolumeData>(voxelized.grid));
    }
};

}  // namespace

void registerVoxelizerNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Voxelizer";
    d.version = 7;
    d.category = "volume";
    d.doc =
        "Splats cloud particles into a sparse OpenVDB fog volume (Sec. 6.3: volume data with "
        "alpha values): a FloatGrid named 'density', class fog volume, background 0, whose "
        "linear transform has the voxel size in metres; voxel (i, j, k) is centred at "
        "(i, j, k) * voxelSize. Each particle adds density * w(r) to every voxel centre at "
        "distance r < radius, with w = (1 - r^2/radius^2)^3 ('smooth', integral "
        "64 pi radius^3 / 315 m^3 per unit density) or w = 1 ('sphere', integral "
        "4/3 pi radius^3); the default 'gaussian' (ours) is w = exp(-r^2 / (2 sigma^2)), sigma = "
        "0.3435 radius, the smooth kernel's peak and integral, made by adding each particle's "
        "trilinear weights to the 8 voxels around it and blurring with separable passes, so a "
        "particle costs the same at any radius (at 4 voxels 19 times less than 'smooth'; the "
        "paper gives no kernel). Sums are clamped to [0, 1] unless clamp is off, then optionally "
        "filtered on the active voxels. Domain warp (ours): with warpAmplitude > 0 the density "
        "is resampled at x + w(x), w a vector fractal of gradient noise in the coordinates of "
        "the copy owning each territory cell, folding the envelope into lobes and overhangs. "
        "Florets (ours): with floretRadius > 0 the surface "
        "v = 0.5 becomes a distance field, sinks by floretRadius (not on faces that look "
        "down), and round lumps of that radius grow back out of it, each carrying "
        "floretChildren lumps of half its radius, floretLevels generations deep, with a "
        "one-voxel edge, each riding the copy whose territory it grows in. Surface detail "
        "(ours): "
        "where the summed density v lies strictly between 0 and 1 (the soft edge of the "
        "splats), Perlin-Worley noise n in [0, 1] erodes it to (v - e) / (1 - e), e = "
        "detailAmplitude (1 - n), evaluated at the voxel's place in its copy (the voxel minus "
        "the copy's origin, R P_f of Eq. 10), so the detail moves with the copies instead of "
        "swimming through them; detailAmplitude 0 leaves the splats untouched. flatBase (ours) "
        "cuts every column at its condensation level; optics 'water' (ours) makes the value the "
        "cloud's liquid water as extinction: (LWC / 1 g m^-3)^(2/3), with LWC the share "
        "adiabaticFraction x value of the moist-adiabatic water above the base, and writes "
        "'extinction' (1/m per unit value, sigma of 1 g/m^3 for the droplets), 'albedo', "
        "'phase_asymmetry' and 'droplet_concentration_cm3' into the metadata; with ice (ours) the "
        "condensate colder than glaciationStart freezes, all of it by glaciationEnd, the cloud "
        "keeps iceRetention of the frozen part as crystals of iceEffectiveRadius, and the value "
        "is the liquid's and the ice's summed extinction over 'extinction'; each horizontal layer "
        "of it is blurred by iceSpread along the outflow's wind and iceSpreadAcross across it, "
        "and every voxel takes its ice share of the blurred "
        "value, so the glaciated anvil is a sheet. Only leaves that "
        "particles touch are allocated; the grid is identical for any thread count. Metadata: "
        "frame, units ('metres'), voxel_size_m, particle_radius_m, kernel, particle_count, and "
        "cloud_base_m with a flat base. See docs/voxelizer.md.";
    d.frameDependent = true;  // the frame is written into the grid's metadata
    d.inputs = {port("particles", "CloudParticles", "the cloud particles, positions in metres"),
                port("condensation", "Condensation",
                     "the condensation levels, for flatBase and optics 'water'", true),
                port("atmosphere", "Atmosphere",
                     "temperature and pressure at the cloud base, for optics 'water'", true)};
    d.outputs = {port("volume", "FogVolume", "the density grid, values in [0, 1] when clamped")};
    d.params = {
        floatParam("voxelSize", 4.0, "m", "voxel edge length (value ours)", 0.01, 1000.0),
        floatParam("radius", 8.0, "m",
                   "kernel radius R of one particle, at most 32 voxels (value ours)", 0.01,
                   10000.0),
        stringParam(
            "kernel", "gaussian",
            "particle profile: smooth = (1 - r^2/R^2)^3, sphere = 1 inside R, gaussian = "
            "exp(-r^2 / (2 (0.3435 R)^2)), the smooth kernel's peak and integral, splatted "
            "by a trilinear deposit and separable blur passes (ours; its cost does not grow "
            "with R^3)",
            {"smooth", "sphere", "gaussian"}),
        floatParam("density", 0.25, "",
                   "density one particle adds at its centre (fog density, 1 = opaque; value ours)",
                   0.0, 1000.0),
        boolParam("clamp", true, "clamp summed density to [0, 1] (a fog volume's range)"),
        floatParam("detailAmplitude", 0.8, "",
                   "largest erosion of the surface's density by the detail noise; 0: no detail "
                   "(value ours)",
                   0.0, 1.0),
        floatParam("detailFrequency", 1.5, "1/radius",
                   "detail noise cycles per particle radius R, first octave (value ours)", 0.05,
                   16.0),
        intParam("detailOctaves", 2, "",
                 "octaves of the detail noise, each twice as fine (value ours)", 1, 8),
        floatParam("warpAmplitude", 0.0, "m",
                   "largest displacement of the warp's first octave: the envelope is resampled "
                   "at points moved by a vector fractal noise in the copies' coordinates, "
                   "bending it into lobes and overhangs (ours); 0: none",
                   0.0, 10000.0),
        floatParam("warpWavelength", 1200.0, "m",
                   "wavelength of the warp's first octave (value ours)", 1.0, 1e6),
        intParam("warpOctaves", 4, "", "octaves of the warp, each half the wavelength (value ours)",
                 1, 8),
        floatParam("warpRoughness", 0.6, "",
                   "amplitude ratio between successive octaves of the warp: the outline's "
                   "dimension is about 2 - log2(1 / roughness) (value ours)",
                   0.05, 1.0),
        floatParam("floretRadius", 0.0, "m",
                   "radius of the largest cauliflower lumps grown on the envelope (ours); 0: "
                   "none",
                   0.0, 10000.0),
        intParam("floretLevels", 4, "",
                 "generations of lumps, each half the radius of the one before (value ours)", 1, 6),
        intParam("floretChildren", 8, "", "lumps on each lump (value ours)", 1, 16),
        boolParam("flatBase", false,
                  "cut the cloud at the condensation level of its column (ours: rising air "
                  "saturates there; the 10th percentile of the condensation heights per "
                  "baseCellSize cell), rising to full density baseTransition above it"),
        floatParam("baseTransition", 20.0, "m",
                   "depth over which the cut at the base rises from 0 to 1 (value ours)", 0.1,
                   10000.0),
        floatParam("baseCellSize", 500.0, "m",
                   "cell of the condensation level's height field (value ours)", 1.0, 1e6),
        stringParam("optics", "density",
                    "density = the splat's value (the Renderer's extinction scales it); water = "
                    "the value is (LWC / 1 g m^-3)^(2/3), LWC = adiabaticFraction x value x the "
                    "moist-adiabatic liquid water above the base (ours), so value x the "
                    "'extinction' metadata is sigma = 3 LWC / (2 rho_w r_eff) (Stephens 1978); "
                    "cuts at the base as flatBase does",
                    {"density", "water"}),
        floatParam("adiabaticFraction", 0.6, "",
                   "water: share of the adiabatic liquid water the cloud holds (real cumulus "
                   "0.3-0.8, Warner 1970; value ours)",
                   0.01, 1.0),
        stringParam("airMass", "continental",
                    "water: droplet spectrum, k = (r_vol / r_eff)^3: continental 0.67, N 500 "
                    "/cm^3; maritime 0.80, N 100 /cm^3 (Martin et al. 1994)",
                    {"continental", "maritime"}),
        floatParam("dropletConcentration", 0.0, "1/cm^3",
                   "water: droplet number N; 0 = the air mass's typical value", 0.0, 10000.0),
        boolParam("ice", true,
                  "water: the condensate freezes where the parcel is colder than "
                  "glaciationStart, all of it below glaciationEnd (ours; docs/voxelizer.md, "
                  "'Ice')"),
        floatParam("glaciationStart", -10.0, "C",
                   "water: first ice, heterogeneous freezing (Pruppacher and Klett 1997)", -100.0,
                   0.0),
        floatParam("glaciationEnd", -38.0, "C",
                   "water: all ice, homogeneous freezing (Pruppacher and Klett 1997)", -100.0, 0.0),
        floatParam("iceRetention", 0.05, "",
                   "water: share of the frozen condensate the cloud keeps as ice, the rest "
                   "falls as snow (value ours: anvils hold about 0.1 g/m^3)",
                   0.001, 1.0),
        floatParam("iceEffectiveRadius", 30.0, "um",
                   "water: ice crystals' effective radius; sigma = 3 IWC / (2 rho_ice r_eff) "
                   "(Fu 1996; anvils 20-60 um)",
                   1.0, 1000.0),
        floatParam("iceSpread", 3000.0, "m",
                   "water: standard deviation of the spreading of the glaciated outflow into a "
                   "sheet along its wind (every way in calm air; ours: docs/voxelizer.md, "
                   "'Ice'); 0: none",
                   0.0, 100000.0),
        floatParam("iceSpreadAcross", 500.0, "m",
                   "water: the same across the outflow's wind, so the sheet is streaked along "
                   "it (value ours)",
                   0.0, 100000.0),
        floatParam("anvilDepth", 2000.0, "m",
                   "water: the spreading starts this far under the equilibrium level of a "
                   "parcel lifted from the ground, full a kilometre higher (value ours: "
                   "outflows are 1-3 km deep)",
                   0.0, 20000.0),
        stringParam("filter", "none", "OpenVDB smoothing of the active voxels after splatting",
                    {"none", "mean", "gaussian", "median"}),
        intParam("filterWidth", 1, "voxels", "filter half-width: the stencil is (2 w + 1)^3", 1, 8),
        intParam("filterIterations", 1, "", "filter passes", 1, 16),
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        if (!(p.getFloat("glaciationEnd") < p.getFloat("glaciationStart")))
            check.fail("glaciationEnd", "glaciationEnd must be colder than glaciationStart");
        if (p.getFloat("radius") > 32.0 * p.getFloat("voxelSize"))
            check.fail("radius", "radius must be at most 32 voxel sizes");
        // The warp grows the active voxels by its reach: bounded before anything is allocated.
        if (algo::domainWarpReach(detailFrom(p, p.getFloat("radius")).warp) >
            64.0 * p.getFloat("voxelSize"))
            check.fail("warpAmplitude",
                       "the warp's reach (warpAmplitude x the octaves' weights) must be at most "
                       "64 voxel sizes");
    };
    d.create = [] { return std::make_unique<VoxelizerNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
