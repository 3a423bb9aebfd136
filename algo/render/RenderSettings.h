#pragma once
/// What the volume renderer needs besides the fog volume: camera, lights, medium, marching.
/// World units are metres, z is up, the ground plane is z = 0. Colours are linear RGB.

#include <cstdint>

#include <openvdb/math/Vec3.h>

namespace cg::algo {

using RenderVec3 = openvdb::math::Vec3<double>;

/// A pinhole camera. Pixel (0, 0) is the top-left corner of the image.
struct RenderCamera {
    RenderVec3 position{0.0, -4000.0, 800.0};  ///< m
    RenderVec3 lookAt{0.0, 0.0, 1200.0};       ///< m; must differ from position
    RenderVec3 up{0.0, 0.0, 1.0};              ///< need not be orthogonal to the view direction
    double fovDegrees = 40.0;                  ///< vertical field of view, in (0, 180)
    int width = 320;                           ///< px
    int height = 240;                          ///< px
};

/// A distant sun: parallel light of irradiance colour * intensity on a surface facing it.
struct RenderSun {
    RenderVec3 direction{1.0, 0.3, 0.35};  ///< toward the sun; normalised by the renderer
    RenderVec3 colour{1.0, 0.95, 0.85};
    double intensity = 20.0;  ///< irradiance scale (linear radiance units × sr)
};

/// The sky dome: radiance blends from the horizon colour (direction z = 0 and below) to the
/// zenith colour as sqrt(z) of the unit view direction. It is what a ray that misses
/// everything sees, unscaled; `ambient` scales only the sky light the cloud and ground receive.
struct RenderSky {
    RenderVec3 zenith{0.16, 0.33, 0.75};
    RenderVec3 horizon{0.55, 0.65, 0.80};
    double ambient = 1.0;    ///< 1 = physically as bright as the visible sky
    double occlusion = 0.3;  ///< sky light inside the cloud falls as exp(−occlusion τ_up)
};

/// An infinite Lambertian ground at z = 0 that receives the cloud's shadow.
struct RenderGround {
    bool enabled = true;
    RenderVec3 albedo{0.13, 0.14, 0.11};
    double hazeDistance = 20000.0;  ///< m; the ground fades to the horizon colour, 0 = off
};

/// The droplets' phase function (Phase.h).
enum class PhaseModel {
    TwoLobeHenyeyGreenstein,  ///< g, g2, lobeBlend
    Mie,                      ///< Jendersie and d'Eon's fit for droplets of dropletDiameter
};

/// The cloud medium: σ_t = extinction × density, σ_s = albedo × σ_t.
struct RenderMedium {
    double extinction = 0.05;  ///< 1/m per unit density
    double albedo = 0.99;      ///< single-scattering albedo
    PhaseModel phase = PhaseModel::TwoLobeHenyeyGreenstein;
    double g = 0.8;                 ///< HG asymmetry of the main (forward) lobe
    double g2 = -0.3;               ///< HG asymmetry of the second (backward) lobe
    double lobeBlend = 0.2;         ///< weight of the second lobe, 0 = single lobe
    double dropletDiameter = 20.0;  ///< μm, with PhaseModel::Mie (fit valid for 5 to 50)
};

/// How the fast renderer approximates light scattered more than once.
enum class MultiScatterModel {
    /// The fluence of scattered sun, sky and ground light solved on a coarse lattice in the
    /// diffusion approximation (RenderDiffusion.h); single scattering of the sun stays exact.
    Diffusion,
    /// Octaves (Wrenninge et al. 2013): octave i adds b^i times the single-scattering term
    /// with the sun's optical depth scaled by a^i and the phase asymmetries by c^i (1 octave =
    /// single scattering only); sky light is occluded by the optical depth straight up and
    /// down.
    Octaves,
};

struct RenderMultiScatter {
    MultiScatterModel model = MultiScatterModel::Diffusion;
    int cellVoxels = 2;  ///< diffusion: lattice cell edge, voxels (grown to fit 2M cells)
    int octaves = 4;
    double attenuation = 0.5;   ///< a
    double contribution = 0.5;  ///< b
    double eccentricity = 0.5;  ///< c
};

/// Ray-marching controls. Steps are in voxels of the fog volume.
struct RenderMarch {
    double step = 0.5;               ///< camera-ray step, voxels
    double lightTexel = 1.0;         ///< light-map texel, voxels (grown if the map would be huge)
    double lightStep = 1.0;          ///< step when filling the light maps, voxels
    bool jitter = true;              ///< offset each pixel's samples by a per-pixel random fraction
    std::uint64_t seed = 0;          ///< seed of that offset and of the path tracer's paths
    double minTransmittance = 1e-3;  ///< stop a ray once less than this gets through
    /// Once less than this gets through, a ray's samples stand for two steps each (0: never).
    double coarseTransmittance = 0.2;
};

/// The reference path tracer (renderPathTraced).
struct RenderPathTrace {
    int samples = 64;       ///< paths per pixel
    int maxBounces = 1000;  ///< scattering events and ground bounces before a path is cut
};

struct RenderSettings {
    RenderCamera camera;
    RenderSun sun;
    RenderSky sky;
    RenderGround ground;
    RenderMedium medium;
    RenderMultiScatter multiScatter;
    RenderMarch march;
    RenderPathTrace pathTrace;
    /// The fast renderer also returns RenderedImage's AOVs (sun and sky parts of the cloud's
    /// light, depth, ground shadow matte).
    bool aovs = false;
};

}  // namespace cg::algo
