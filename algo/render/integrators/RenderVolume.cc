#include "algo/render/integrators/RenderVolume.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"
#include "algo/render/RenderRays.h"
#include "algo/render/lighting/DiffuseLight.h"
#include "algo/render/lighting/RenderDiffusion.h"
#include "algo/render/lighting/RenderLightMap.h"
#include "algo/render/media/Phase.h"
#include "algo/render/media/RenderOccupancy.h"
#include "algo/render/media/TrilinearDensity.h"

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxOctaves = 16;

using Span = RenderOccupancy::Span;

void require(bool ok, const std::string& what)
{
    if (!ok) throw std::invalid_argument(what);
}

/// The most lattice cells one camera sample stands for.
constexpr int kMaxStride = 8;

/// Visits density samples on the lattice t_k = (k + offset) dt, t in [0, tMax), inside the
/// occupied spans; each sample stands for the interval [t - dt/2, t + dt/2]. fn(t, density,
/// width) returns how many cells of the lattice the samples should stand for from then on (a
/// power of two; 0: stop); a sample of `stride` cells k .. k + stride - 1 is taken at their
/// middle (width stride dt), with k a multiple of the stride. The lattice and its groups are
/// global along the ray, so span boundaries leave no seams and how the spans are cut does
/// not move a sample: at a span's first cell that is not a multiple of the stride, and
/// until a multiple of the larger stride fn asks for, the march takes the largest stride
/// that fits. Zero-density samples are skipped.
template <class Fn>
void marchRay(const RenderOccupancy& occ, TrilinearDensity& sampler, const IndexRay& ray,
              double tMax, double dt, double offset, std::vector<Span>& spans, Fn&& fn)
{
    spans.clear();
    occ.spans(ray.o, ray.d, 0.0, tMax, spans);
    // k is a whole number and the strides powers of two: a mask in place of fmod.
    const auto alignedTo = [](double k, int stride) {
        return (static_cast<std::int64_t>(k) & (stride - 1)) == 0;
    };
    int stride = 1, wanted = 1;
    for (const Span& s : spans) {
        for (double k = std::ceil(s.t0 / dt - offset); (k + offset) * dt < s.t1;) {
            while (!alignedTo(k, stride)) stride /= 2;
            while (stride < wanted && alignedTo(k, 2 * stride)) stride *= 2;
            const double t = (k + offset + 0.5 * (stride - 1)) * dt;
            const double density = sampler.sample(ray.o + ray.d * t);
            k += stride;
            if (!(density > 0.0)) continue;
            const int next = fn(t, density, stride * dt);
            if (next == 0) return;
            wanted = std::max(wanted, next);
        }
    }
}

/// Where shade() puts a pixel's AOVs (RenderedImage), or nullptr without them.
struct PixelAovs {
    float* sun = nullptr;     ///< 3 floats
    float* sky = nullptr;     ///< 3 floats
    float* depth = nullptr;   ///< 1 float
    float* shadow = nullptr;  ///< 1 float
};

/// The lights the diffusion solves for, split by where their light comes from: the sun
/// (directly, or off the sun-lit ground) or the sky.
bool fromSun(int light)
{
    return light == RenderDiffusion::Sun || light == RenderDiffusion::LitGround ||
           light == RenderDiffusion::SunGlowGround;
}

/// Everything constant over a frame.
struct Frame {
    const RenderSettings& s;
    const openvdb::FloatGrid& grid;
    RenderOccupancy occupancy;
    RenderLightMap sunMap;
    RenderLightMap skyMap;
    DiffuseLight diffuse;  ///< with MultiScatterModel::Diffusion
    /// With AOVs: the diffuse light of the sun's lights alone (the sky's is the rest).
    DiffuseLight diffuseSun;
    bool useDiffusion = false;
    PhaseFunction phase;
    std::optional<PhaseTwice> phaseTwice;  ///< with the diffusion model
    DeltaEddington split;                  ///< of the phase function
    double peakless = 1.0;  ///< 1 − ω f: the sun beam's extinction, forward peak f out
    double dt = 1.0;
    RenderVec3 sunDir;         ///< unit, toward the sun
    RenderVec3 sunIrradiance;  ///< colour × intensity
    RenderVec3 skyUp;          ///< ambient × mean radiance of the upper sky hemisphere
    RenderVec3 below;          ///< ambient × radiance from below (ground bounce or horizon)
    RenderVec3 belowSun;       ///< the part of `below` the sun lights (the sun-lit ground)
    RenderVec3 forward;        ///< the camera's unit view axis (depth AOV)
    RenderVec3 groundSky;      ///< ground radiance from sky light alone
    double groundSun = 0.0;    ///< cos of the sun's zenith angle, clamped at 0
    CameraRays rays;
    int octaves = 1;
    double octaveWeight[kMaxOctaves];  ///< b^i
    double octaveAtten[kMaxOctaves];   ///< a^i
    double octaveEcc[kMaxOctaves];     ///< c^i

    Frame(const openvdb::FloatGrid& g, const RenderSettings& settings,
          const std::function<bool()>& cancelled)
        : s(settings),
          grid(g),
          occupancy(g.tree()),
          phase(phaseOf(settings.medium)),
          rays(settings.camera)
    {
        const double voxel = renderVoxelSize(g);
        require(s.march.step > 0.0, "step must be positive");
        dt = s.march.step * voxel;

        require(s.sun.direction.length() > 0.0, "sun direction is zero");
        sunDir = s.sun.direction.unitSafe();
        sunIrradiance = s.sun.colour * s.sun.intensity;
        useDiffusion = s.multiScatter.model == MultiScatterModel::Diffusion;
        octaves = useDiffusion ? 1 : std::clamp(s.multiScatter.octaves, 1, kMaxOctaves);
        for (int i = 0; i < octaves; ++i) {
            octaveWeight[i] = std::pow(s.multiScatter.contribution, i);
            octaveAtten[i] = std::pow(s.multiScatter.attenuation, i);
            octaveEcc[i] = std::pow(s.multiScatter.eccentricity, i);
        }

        // Sky light: with radiance h + (z - h) sqrt(mu) over the upper hemisphere, the mean
        // radiance is h/3 + 2z/3 and the irradiance on the ground is pi (0.2 h + 0.8 z).
        const RenderVec3& h = s.sky.horizon;
        const RenderVec3& z = s.sky.zenith;
        skyUp = (h * (1.0 / 3.0) + z * (2.0 / 3.0)) * s.sky.ambient;
        groundSun = std::max(0.0, sunDir.z());
        groundSky = s.ground.albedo * (h * 0.2 + z * 0.8) * s.sky.ambient;
        if (s.ground.enabled) {
            const RenderVec3 groundLit =
                s.ground.albedo * sunIrradiance * (groundSun / kPi) + groundSky;
            below = groundLit;
            belowSun = groundLit - groundSky;
        } else {
            below = h * s.sky.ambient;
        }

        const bool needSun = s.sun.intensity > 0.0;
        const bool needSky = !useDiffusion && s.sky.ambient > 0.0 && s.sky.occlusion > 0.0;
        if (needSun)
            sunMap = RenderLightMap(g, occupancy, sunDir, s.medium.extinction, s.march.lightTexel,
                                    s.march.lightStep, std::size_t(8) << 20, cancelled);
        const bool litGround = s.ground.enabled && needSun && groundSun > 0.0;
        split = phase.deltaEddington();
        peakless = 1.0 - s.medium.albedo * split.peak;
        if (useDiffusion) {
            phaseTwice.emplace(phase);
            // What each light's unit stands for: the sun's irradiance; the radiance of the
            // sky's mean above, of the open ground (or the horizon without one), of the
            // sun-lit ground's sun part; the ground's albedo, which colours the clouds' glow
            // of the sun and of the sky on it.
            const RenderVec3 radiance[RenderDiffusion::kLights] = {
                sunIrradiance,
                skyUp,
                s.ground.enabled ? groundSky : below,
                litGround ? s.ground.albedo * sunIrradiance * (groundSun / kPi) : RenderVec3(0.0),
                s.ground.albedo * sunIrradiance,
                s.ground.albedo * skyUp};
            const RenderDiffusion solved(g, sunMap, s.medium, s.multiScatter.cellVoxels,
                                         {s.ground.enabled, litGround}, cancelled);
            diffuse = solved.coloured(radiance);
            if (s.aovs) {
                RenderVec3 sunOnly[RenderDiffusion::kLights];
                for (int l = 0; l < RenderDiffusion::kLights; ++l)
                    sunOnly[l] = fromSun(l) ? radiance[l] : RenderVec3(0.0);
                diffuseSun = solved.coloured(sunOnly);
            }
        }
        forward = (s.camera.lookAt - s.camera.position).unitSafe();
        if (needSky)
            skyMap = RenderLightMap(g, occupancy, RenderVec3(0, 0, 1), s.medium.extinction,
                                    s.march.lightTexel * 4.0, s.march.lightStep * 2.0,
                                    std::size_t(4) << 20, cancelled);
    }

    /// The sun's share of the diffuse light `all` scatters toward the camera in channel c. The
    /// fields add (the sky's is all's less the sun's), but the radiance a field scatters is
    /// not linear in it (DiffuseLight.h: a lobe of mean cosine |F| / φ), so each light's own
    /// lobe is scattered and the total shared in their proportion: the parts add up to the
    /// cloud's light exactly.
    double sunShare(const DiffuseLight::Sample& sun, const DiffuseLight::Sample& all, int c,
                    const RenderVec3& dir) const
    {
        const double bySun = diffuseScattered(sun.phi[c], sun.flux[c], -dir, split);
        const double bySky =
            diffuseScattered(all.phi[c] - sun.phi[c], all.flux[c] - sun.flux[c], -dir, split);
        return bySun + bySky > 0.0 ? bySun / (bySun + bySky) : 0.0;
    }

    /// Radiance behind the volume: the lit, shadowed, hazed ground, or the sky; `matte` (if not
    /// null) the fraction of the direct sun the cloud's shadow takes from that ground.
    RenderVec3 background(const RenderVec3& dir, double tGround, float* matte = nullptr) const
    {
        if (matte != nullptr) *matte = 0.0f;
        if (!std::isfinite(tGround)) return skyRadiance(s.sky, dir);
        const RenderVec3 p = s.camera.position + dir * tGround;
        // The sun light scattered into the phase function's forward peak on the way reaches
        // the ground as if unscattered (δ-Eddington): a cloud's shadow is lighter at its thin
        // edges than its optical depth alone says.
        const double sunT = std::exp(-peakless * sunMap.opticalDepth(p));
        if (matte != nullptr && groundSun > 0.0 && !sunMap.empty())
            *matte = static_cast<float>(1.0 - sunT);
        return hazedGround(s,
                           s.ground.albedo * sunIrradiance * (groundSun * sunT / kPi) +
                               diffuse.groundAmbient(p, groundSky),
                           tGround);
    }

    void shade(int px, int py, TrilinearDensity& sampler, std::vector<Span>& spans, float* out,
               float* behind, const PixelAovs& aov) const
    {
        const bool aovs = aov.sun != nullptr;
        const RenderVec3 dir = rays.direction(px, py);
        const RenderVec3& origin = s.camera.position;
        const double tGround = groundDistance(s.ground, origin, dir);

        // The phase functions depend only on the angle between sun light and the view ray.
        const double cosTheta = sunDir.dot(dir);
        double sunPhase[kMaxOctaves];
        // Only the diffusion model splits off the peak.
        const double peakPhase = phaseTwice ? (*phaseTwice)(cosTheta) : 0.0;
        for (int i = 0; i < octaves; ++i)
            sunPhase[i] = octaveWeight[i] * phase.narrowed(octaveEcc[i])(cosTheta);
        const std::uint64_t pixel =
            static_cast<std::uint64_t>(py) * static_cast<std::uint64_t>(s.camera.width) +
            static_cast<std::uint64_t>(px);
        const double offset =
            s.march.jitter ? counterUniform(s.march.seed, 0x52656e646572ull, pixel) : 0.5;

        const double ext = s.medium.extinction;
        const double albedo = s.medium.albedo;
        const double minT = s.march.minTransmittance;
        const double coarseT = s.march.coarseTransmittance;
        // What the rest of the ray adds is at most T of the pixel: below coarseT, samples
        // twice as far apart change it by little, and each halving of T doubles the
        // distance again (up to kMaxStride steps); below minT the ray stops.
        const auto next = [&](double T) {
            if (T < minT) return 0;
            int stride = 1;
            for (double limit = coarseT; T < limit && stride < kMaxStride; limit *= 0.5)
                stride *= 2;
            return stride;
        };
        const bool skyOcclusion = !skyMap.empty();
        double T = 1.0;
        RenderVec3 L(0.0);
        // AOVs: the sun's part of L, and the opacity-weighted sum of the samples' depths.
        RenderVec3 Lsun(0.0);
        double depthSum = 0.0;
        const auto addAovs = [&](double t, double segT, const RenderVec3& sunSource) {
            const double weight = T * (1.0 - segT);
            Lsun += sunSource * (weight * albedo);
            depthSum += weight * t * dir.dot(forward);
        };
        marchRay(
            occupancy, sampler, toIndexRay(grid.transform(), origin, dir), tGround, dt, offset,
            spans, [&](double t, double density, double width) {
                const double sigmaT = ext * density;
                const double segT = std::exp(-sigmaT * width);
                const RenderVec3 p = origin + dir * t;
                const double tauSun = sunMap.opticalDepth(p);
                if (useDiffusion) {
                    // One octave. Sun light scattered into the phase function's forward
                    // peak goes on along the sun's beam (δ-Eddington), a little spread:
                    // it scatters toward the camera as if scattered twice in a row.
                    const double sunT = std::exp(-tauSun);
                    const double peaked = std::exp(-peakless * tauSun) - sunT;
                    RenderVec3 source = sunIrradiance * (sunPhase[0] * sunT + peakPhase * peaked);
                    const DiffuseLight::Sample field = diffuse.at(p);
                    // The sun's field is looked up once a sample, for all three channels.
                    const DiffuseLight::Sample fromSun = aovs ? diffuseSun.at(p) : field;
                    RenderVec3 sunSource = source;
                    for (int c = 0; c < 3; ++c) {
                        const double scattered =
                            diffuseScattered(field.phi[c], field.flux[c], -dir, split);
                        if (aovs) sunSource[c] += sunShare(fromSun, field, c, dir) * scattered;
                        source[c] += scattered;
                    }
                    if (aovs) addAovs(t, segT, sunSource);
                    L += source * (T * albedo * (1.0 - segT));
                    T *= segT;
                    return next(T);
                }
                double sun = 0.0;
                for (int i = 0; i < octaves; ++i)
                    sun += sunPhase[i] * std::exp(-octaveAtten[i] * tauSun);
                // Sky light from above and bounce light from below, each dimmed by the
                // optical depth of the cloud above or below the sample.
                double upT = 1.0, downT = 1.0;
                if (skyOcclusion) {
                    const double tauUp = skyMap.opticalDepth(p);
                    const double down = std::max(0.0, skyMap.columnDepth(p) - tauUp);
                    upT = std::exp(-s.sky.occlusion * tauUp);
                    downT = std::exp(-s.sky.occlusion * down);
                }
                const RenderVec3 source = sunIrradiance * sun + (skyUp * upT + below * downT) * 0.5;
                if (aovs) addAovs(t, segT, sunIrradiance * sun + belowSun * (downT * 0.5));
                // Source constant over the step: ∫ T σ_s S ds = T albedo S (1 − segT).
                L += source * (T * albedo * (1.0 - segT));
                T *= segT;
                return next(T);
            });
        const RenderVec3 bg = background(dir, tGround, aov.shadow);
        if (aovs) {
            // The sky's part is what is left of the cloud's light: its own sum would only
            // differ by rounding (the lights' split is linear).
            const RenderVec3 Lsky = L - Lsun;
            for (int c = 0; c < 3; ++c) {
                aov.sun[c] = static_cast<float>(Lsun[c]);
                aov.sky[c] = static_cast<float>(Lsky[c]);
            }
            const double opacity = 1.0 - T;
            *aov.depth = opacity > 0.0            ? static_cast<float>(depthSum / opacity)
                         : std::isfinite(tGround) ? static_cast<float>(tGround * dir.dot(forward))
                                                  : kNoDepth;
        }
        L += bg * T;
        behind[0] = static_cast<float>(bg.x());
        behind[1] = static_cast<float>(bg.y());
        behind[2] = static_cast<float>(bg.z());
        out[0] = static_cast<float>(L.x());
        out[1] = static_cast<float>(L.y());
        out[2] = static_cast<float>(L.z());
        out[3] = static_cast<float>(1.0 - T);
    }
};

}  // namespace

RenderedImage renderFogVolume(const openvdb::FloatGrid& grid, const RenderSettings& settings,
                              const std::function<bool()>& cancelled)
{
    const Frame frame(grid, settings, cancelled);
    RenderedImage img;
    img.width = settings.camera.width;
    img.height = settings.camera.height;
    const auto w = static_cast<std::size_t>(img.width);
    img.rgba.assign(w * static_cast<std::size_t>(img.height) * 4, 0.0f);
    img.background.assign(w * static_cast<std::size_t>(img.height) * 3, 0.0f);
    if (settings.aovs) {
        const std::size_t n = w * static_cast<std::size_t>(img.height);
        img.sun.assign(3 * n, 0.0f);
        img.sky.assign(3 * n, 0.0f);
        img.depth.assign(n, 0.0f);
        img.shadow.assign(n, 0.0f);
    }
    tbb::parallel_for(
        tbb::blocked_range<int>(0, img.height, 1), [&](const tbb::blocked_range<int>& rows) {
            TrilinearDensity sampler(grid, frame.occupancy);
            std::vector<Span> spans;
            for (int py = rows.begin(); py != rows.end(); ++py) {
                if (cancelled && cancelled()) return;
                const auto y = static_cast<std::size_t>(py);
                float* row = img.rgba.data() + y * w * 4;
                float* behind = img.background.data() + y * w * 3;
                for (int px = 0; px < img.width; ++px) {
                    PixelAovs aov;
                    if (settings.aovs) {
                        const std::size_t i = y * w + static_cast<std::size_t>(px);
                        aov = {&img.sun[3 * i], &img.sky[3 * i], &img.depth[i], &img.shadow[i]};
                    }
                    frame.shade(px, py, sampler, spans, row + 4 * px, behind + 3 * px, aov);
                }
            }
        });
    return img;
}

double fogTransmittance(const openvdb::FloatGrid& grid, const RenderVec3& origin,
                        const RenderVec3& direction, double extinction, double stepVoxels)
{
    require(stepVoxels > 0.0, "step must be positive");
    require(direction.length() > 0.0, "direction is zero");
    const double dt = stepVoxels * renderVoxelSize(grid);
    const RenderOccupancy occ(grid.tree());
    TrilinearDensity sampler(grid, occ);
    std::vector<Span> spans;
    double tau = 0.0;
    marchRay(occ, sampler, toIndexRay(grid.transform(), origin, direction.unitSafe()),
             std::numeric_limits<double>::infinity(), dt, 0.5, spans,
             [&](double, double d, double width) {
                 tau += extinction * d * width;
                 return 1;
             });
    return std::exp(-tau);
}

}  // namespace cg::algo
