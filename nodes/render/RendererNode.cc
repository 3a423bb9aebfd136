// Renderer: a fog volume to a linear-radiance image (sun, sky, ground, multiple scattering).

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "algo/render/integrators/RenderPathTrace.h"
#include "algo/render/integrators/RenderVolume.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CameraPath.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "nodes/render/CameraParams.h"
#include "nodes/render/RenderNodes.h"
#include "nodes/render/ShotJson.h"

namespace cg {

namespace {

algo::RenderVec3 vec(const ParamSet& p, const char* name)
{
    const Vec3 v = p.getVec3(name);
    return {v[0], v[1], v[2]};
}

algo::RenderSettings settingsFrom(const ParamSet& p)
{
    algo::RenderSettings s;
    s.camera.position = vec(p, "cameraPosition");
    s.camera.lookAt = vec(p, "cameraLookAt");
    s.camera.up = vec(p, "cameraUp");
    s.camera.fovDegrees = p.getFloat("fov");
    s.camera.width = static_cast<int>(p.getInt("width"));
    s.camera.height = static_cast<int>(p.getInt("height"));
    s.sun.direction = vec(p, "sunDirection");
    s.sun.colour = vec(p, "sunColour");
    s.sun.intensity = p.getFloat("sunIntensity");
    s.sky.zenith = vec(p, "skyZenith");
    s.sky.horizon = vec(p, "skyHorizon");
    s.sky.ambient = p.getFloat("ambient");
    s.sky.occlusion = p.getFloat("skyOcclusion");
    s.ground.enabled = p.getBool("ground");
    s.ground.albedo = vec(p, "groundAlbedo");
    s.ground.hazeDistance = p.getFloat("hazeDistance");
    s.medium.extinction = p.getFloat("extinction");
    s.medium.albedo = p.getFloat("albedo");
    s.medium.phase = p.getString("phase") == "mie" ? algo::PhaseModel::Mie
                                                   : algo::PhaseModel::TwoLobeHenyeyGreenstein;
    s.medium.dropletDiameter = p.getFloat("dropletDiameter");
    s.medium.g = p.getFloat("g");
    s.medium.g2 = p.getFloat("g2");
    s.medium.lobeBlend = p.getFloat("lobeBlend");
    s.multiScatter.model = p.getString("multipleScattering") == "octaves"
                               ? algo::MultiScatterModel::Octaves
                               : algo::MultiScatterModel::Diffusion;
    s.multiScatter.octaves = static_cast<int>(p.getInt("octaves"));
    s.multiScatter.attenuation = p.getFloat("msAttenuation");
    s.multiScatter.contribution = p.getFloat("msContribution");
    s.multiScatter.eccentricity = p.getFloat("msEccentricity");
    s.march.step = p.getFloat("step");
    s.march.coarseTransmittance = p.getFloat("coarseTransmittance");
    s.march.lightTexel = p.getFloat("lightTexel");
    s.march.lightStep = p.getFloat("lightStep");
    s.march.jitter = p.getBool("jitter");
    s.march.seed = static_cast<std::uint64_t>(p.getInt("jitterSeed"));
    s.pathTrace.samples = static_cast<int>(p.getInt("samples"));
    s.pathTrace.maxBounces = static_cast<int>(p.getInt("maxBounces"));
    s.aovs = p.getBool("aovs");
    return s;
}

/// The volume's own optics, where its metadata has them (the Voxelizer's optics 'water'):
/// 'extinction' (1/m per unit value) and 'albedo' replace the parameters.
void takeVolumeOptics(const openvdb::FloatGrid& grid, algo::RenderMedium& medium,
                      const CookContext& ctx)
{
    const auto take = [&](const char* name, double max, double& into) {
        const auto m = grid.getMetadata<openvdb::FloatMetadata>(name);
        if (!m) return;
        if (!(m->value() >= 0.0f && m->value() <= max))
            throw InputError(ctx.nodeId() + "/inputs/volume",
                             std::string("the volume's '") + name + "' metadata must be in [0, " +
                                 std::to_string(static_cast<int>(max)) +
                                 "] (or set volumeOptics false)");
        into = m->value();
    };
    take("extinction", 1e3, medium.extinction);
    take("albedo", 1.0, medium.albedo);
}

class RendererNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto volume = ctx.input<FogVolumeData>("volume");
        algo::RenderSettings settings = settingsFrom(ctx.params());
        const auto path = std::make_shared<CameraPathData>(
            cameraKeysFrom(ctx.params()), settings.camera.width, settings.camera.height,
            ctx.params().getBool("cameraEase"));
        settings.camera = path->at(ctx.frame());
        if (ctx.params().getBool("volumeOptics"))
            takeVolumeOptics(*volume->grid, settings.medium, ctx);
        const bool pathTrace = ctx.params().getString("mode") == "pathtrace";
        const auto cancelled = [&ctx] { return ctx.cancelToken().cancelled(); };
        algo::RenderedImage img = pathTrace
                                      ? algo::renderPathTraced(*volume->grid, settings, cancelled)
                                      : algo::renderFogVolume(*volume->grid, settings, cancelled);
        ctx.checkCancelled();
        ImageAovs aovs{std::move(img.sun), std::move(img.sky), std::move(img.depth),
                       std::move(img.shadow)};
        ctx.setOutput("image", std::make_shared<ImageData>(
                                   img.width, img.height, std::move(img.rgba),
                                   std::move(img.background), settings.camera, std::move(aovs)));
        ctx.setOutput("camera", path);
        ctx.setOutput("lighting", std::make_shared<TextData>(lightingJson(settings)));
    }
};

}  // namespace

void registerRendererNode(Registry& registry)
{
    const algo::RenderSettings def;
    const auto v3 = [](const algo::RenderVec3& v) { return Vec3{v.x(), v.y(), v.z()}; };
    NodeDecl d;
    d.type = "Renderer";
    d.version = 23;  // each version's change: CHANGES.md, "Node versions"
    d.category = "render";
    d.framesInAnyOrder = true;
    // A moving camera makes each frame differ; a still one renders a still volume once.
    d.frameDependentIf = [](const ParamSet& p) {
        return !p.getString("cameraFile").empty() || !p.getFloatList("cameraKeys").empty();
    };
    d.doc =
        "Ray-marches a fog volume (sigma_t = extinction x density, sigma_s = albedo x sigma_t) "
        "with empty-space skipping over 8^3-voxel blocks, and over 2^3-voxel bricks where no "
        "sample "
        "can be positive. Each sample scatters sun light "
        "(two-lobe Henyey-Greenstein phase by default; optical depth toward the sun from a "
        "light map precomputed per frame) and the multiply scattered light of sun, sky and "
        "ground: by default a flux-limited diffusion solved once a frame on a coarse lattice "
        "whose surface faces see the sky, the ground and the other clouds (ours, checked "
        "against mode pathtrace in docs/rendering.md), or Wrenninge et al. 2013's octaves "
        "with sky light straight up and down (multipleScattering octaves). Behind the volume: "
        "the ground z = 0 (lit by sun, sky and the clouds above it, with the clouds' shadows, "
        "hazed with distance) or a zenith/horizon sky gradient. mode pathtrace is the "
        "reference: an unbiased volumetric path tracer of the same scene. Output: "
        "linear radiance RGBA, top row first, before exposure and tone map (WriteImage applies "
        "them); alpha is the volume's opacity 1 - T. The image also carries the background "
        "alone (the radiance behind the volume), so WriteImage can write the cloud as a "
        "premultiplied layer of its own: beauty = cloud + (1 - alpha) x background. Independent "
        "of the thread count. See docs/rendering.md.";
    d.inputs = {port("volume", "FogVolume", "the cloud density (fog volume, metres)")};
    d.outputs = {port("image", "Image",
                      "linear radiance RGBA, alpha = volume opacity, with the background and "
                      "the frame's camera"),
                 port("camera", "CameraPath",
                      "the camera over the whole shot, for WriteCamera (the same every frame)"),
                 port("lighting", "Text",
                      "the sun, sky, ground and the medium's optics as JSON, for WriteShot")};
    d.params = {
        stringParam("mode", "fast",
                    "fast = the ray marcher with light maps and the multiple-scattering model; "
                    "pathtrace = the "
                    "reference path tracer (unbiased, slow; samples and maxBounces)",
                    {"fast", "pathtrace"}),
        intParam("width", def.camera.width, "px", "image width", 1, 16384),
        intParam("height", def.camera.height, "px", "image height", 1, 16384),
        floatParam("fov", def.camera.fovDegrees, "deg", "vertical field of view", 1, 170),
        vec3Param("cameraPosition", v3(def.camera.position), "m", "camera position (z up)"),
        vec3Param("cameraLookAt", v3(def.camera.lookAt), "m", "point at the image centre"),
        vec3Param("cameraUp", v3(def.camera.up), "",
                  "up direction (any length, not along the view)"),
        floatListParam(
            "cameraKeys", {}, "",
            "camera moves (ours): keys of 8 numbers each, frame, position x y z, look-at x y z, "
            "vertical field of view (cameraUp for all); a cubic Hermite path with Catmull-Rom "
            "tangents through them, held before the first and after the last; a key's frame "
            "renders exactly as the static camera set to it. Empty: the static camera"),
        inputFileParam("cameraFile", "",
                       "a Nuke .chan camera (frame, translate, rotate ZXY in degrees, vertical "
                       "field of view; y up, as Nuke, Houdini, Maya and Blender's add-on write "
                       "it): each line is a key; replaces the camera parameters. A relative "
                       "path is found beside the graph file"),
        boolParam("cameraEase", false,
                  "camera moves (ours): the path starts from rest at the first key and comes to "
                  "rest at the last (zero tangents there; the inner keys keep theirs), as a "
                  "move keyed from a hold; off: the end tangents point at the next key, so the "
                  "camera starts and stops at speed"),
        vec3Param("sunDirection", v3(def.sun.direction), "",
                  "direction toward the sun (normalised; z > 0 above the horizon)"),
        vec3Param("sunColour", v3(def.sun.colour), "", "sun colour, linear RGB", 0, 100),
        floatParam("sunIntensity", def.sun.intensity, "",
                   "sun irradiance scale: a white surface facing the sun has radiance "
                   "colour x intensity / pi (our choice)",
                   0, 1e6),
        vec3Param("skyZenith", v3(def.sky.zenith), "", "sky radiance straight up, linear RGB", 0,
                  1e6),
        vec3Param("skyHorizon", v3(def.sky.horizon), "",
                  "sky radiance at and below the horizon, linear RGB", 0, 1e6),
        floatParam("ambient", def.sky.ambient, "",
                   "scale of the sky light received by cloud and ground (1 = physical)", 0, 100),
        floatParam("skyOcclusion", def.sky.occlusion, "",
                   "sky light in the cloud falls as exp(-skyOcclusion x optical depth up)", 0, 10),
        boolParam("ground", def.ground.enabled, "draw the ground plane z = 0 with cloud shadows"),
        vec3Param("groundAlbedo", v3(def.ground.albedo), "", "ground reflectance, linear RGB", 0,
                  1),
        floatParam("hazeDistance", def.ground.hazeDistance, "m",
                   "the ground fades to the horizon colour as exp(-distance / this); 0 = off", 0,
                   1e7),
        floatParam("extinction", def.medium.extinction, "1/m",
                   "extinction coefficient per unit density (0.05 ~ cumulus liquid water)", 0, 1e3),
        boolParam("volumeOptics", true,
                  "use the volume's 'extinction' (1/m per unit value) and 'albedo' metadata, "
                  "written by the Voxelizer's optics 'water', in place of those parameters "
                  "where it has them"),
        floatParam("albedo", def.medium.albedo, "", "single-scattering albedo", 0, 1),
        stringParam(
            "phase", "twoLobeHG",
            "phase function: twoLobeHG = (1 - lobeBlend) HG(g) + lobeBlend HG(g2); mie = "
            "Jendersie and d'Eon's 2023 fit to Mie scattering by droplets of "
            "dropletDiameter (HG + Draine; sharper silver lining, a backward glory lobe; the "
            "fast mode is not yet within 10% of pathtrace with it, docs/rendering.md)",
            {"twoLobeHG", "mie"}),
        floatParam("g", def.medium.g, "", "twoLobeHG: asymmetry of the forward HG lobe", -0.99,
                   0.99),
        floatParam("g2", def.medium.g2, "", "twoLobeHG: asymmetry of the second HG lobe", -0.99,
                   0.99),
        floatParam("lobeBlend", def.medium.lobeBlend, "",
                   "twoLobeHG: weight of the second lobe, 0 = one lobe", 0, 1),
        floatParam("dropletDiameter", def.medium.dropletDiameter, "um",
                   "mie: droplet diameter (the fit holds from 5 to 50; cumulus 10-30, our "
                   "default 20)",
                   5, 50),
        stringParam("multipleScattering", "diffusion",
                    "fast mode: diffusion = the fluence of scattered sun, sky and ground light "
                    "solved on a coarse lattice (ours, checked against pathtrace); octaves = "
                    "Wrenninge et al. 2013 with sky light straight up and down (the octave and "
                    "skyOcclusion parameters apply only to it)",
                    {"diffusion", "octaves"}),
        intParam("octaves", def.multiScatter.octaves, "",
                 "multiple-scattering octaves (1 = single scattering)", 1, 16),
        floatParam("msAttenuation", def.multiScatter.attenuation, "",
                   "a: octave i sees the sun's optical depth x a^i", 0, 1),
        floatParam("msContribution", def.multiScatter.contribution, "",
                   "b: octave i is weighted b^i", 0, 1),
        floatParam("msEccentricity", def.multiScatter.eccentricity, "",
                   "c: octave i has phase asymmetry x c^i", 0, 1),
        floatParam("step", def.march.step, "voxels", "camera-ray step", 0.05, 16),
        floatParam("coarseTransmittance", def.march.coarseTransmittance, "",
                   "once a camera ray lets less than this through, each of its samples stands "
                   "for two steps, and for twice as many at each halving of what gets through, "
                   "up to 8 (what is left of the ray adds at most this fraction of the pixel; "
                   "0: never)",
                   0, 1),
        floatParam("lightTexel", def.march.lightTexel, "voxels",
                   "texel of the sun light map (grown if the map would exceed 8M texels)", 0.25,
                   64),
        floatParam("lightStep", def.march.lightStep, "voxels", "step when filling the light maps",
                   0.1, 16),
        boolParam("jitter", def.march.jitter,
                  "offset each pixel's samples by a per-pixel random fraction of a step "
                  "(turns banding into fine grain)"),
        intParam("jitterSeed", 0, "",
                 "seed of the jitter and of the path tracer's paths (counter-based on the pixel "
                 "index)",
                 0, 1e15),
        intParam("samples", def.pathTrace.samples, "",
                 "pathtrace: paths a pixel (noise falls as 1/sqrt(samples))", 1, 1 << 20),
        intParam("maxBounces", def.pathTrace.maxBounces, "",
                 "pathtrace: events a path may have before it is cut (thick cumulus needs "
                 "hundreds; Russian roulette ends most paths long before)",
                 1, 1 << 20),
        boolParam("aovs", false,
                  "fast mode (ours): also the cloud's light from the sun and from the sky "
                  "(their sum is the cloud layer), its depth (camera-space, m, the opacity-"
                  "weighted mean of its samples' depths; the ground's where no cloud, 1e10 on "
                  "the sky) and the ground's shadow matte (the fraction of the direct sun the "
                  "cloud takes), for WriteImage's EXR layers; costs one more light lookup a "
                  "sample"),
    };
    d.hashExtra = hashCameraFile;
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        checkCameraParams(p, check);
        // RGBA and the background: 7 floats a pixel; the AOVs 8 more.
        const bool aovs = p.getBool("aovs");
        check.checkAllocation("width", {p.getInt("width"), p.getInt("height")},
                              (aovs ? 15 : 7) * sizeof(float));
        if (aovs && p.getString("mode") != "fast")
            check.fail("aovs",
                       "only the fast mode makes AOVs (mode is '" + p.getString("mode") + "')");
        const Vec3 a = p.getVec3("cameraPosition"), b = p.getVec3("cameraLookAt");
        if (a == b) check.fail("cameraLookAt", "equals cameraPosition");
        const Vec3 s = p.getVec3("sunDirection");
        if (s[0] == 0.0 && s[1] == 0.0 && s[2] == 0.0) check.fail("sunDirection", "is zero");
        const Vec3 u = p.getVec3("cameraUp");
        const double vx = b[0] - a[0], vy = b[1] - a[1], vz = b[2] - a[2];
        const double cx = vy * u[2] - vz * u[1], cy = vz * u[0] - vx * u[2],
                     cz = vx * u[1] - vy * u[0];
        if (cx * cx + cy * cy + cz * cz == 0.0)
            check.fail("cameraUp", "is zero or along the view direction");
    };
    d.create = [] { return std::make_unique<RendererNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
