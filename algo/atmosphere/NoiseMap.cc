#include "algo/atmosphere/NoiseMap.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>

#include "algo/CounterRandom.h"

namespace cg::algo {

namespace {

// FFTW's planner (plan creation and destruction) is not thread-safe; fftw_execute is.
std::mutex& fftwPlannerMutex()
{
    static std::mutex m;
    return m;
}

struct FftwFree {
    void operator()(void* p) const { fftw_free(p); }
};
using RealBuffer = std::unique_ptr<double[], FftwFree>;
using ComplexBuffer = std::unique_ptr<fftw_complex[], FftwFree>;

class Plan {
public:
    explicit Plan(fftw_plan p) : mPlan(p) {}
    ~Plan()
    {
        std::lock_guard<std::mutex> lock(fftwPlannerMutex());
        fftw_destroy_plan(mPlan);
    }
    Plan(const Plan&) = delete;
    Plan& operator=(const Plan&) = delete;
    void execute() const { fftw_execute(mPlan); }

private:
    fftw_plan mPlan;
};

constexpr std::uint64_t kNoiseStream = 0x6e6f6973654d6170ull;  // "noiseMap"
constexpr std::size_t kCancelEvery = std::size_t(1) << 16;

/// Min-max normalisation in place to [0, 1]; a constant field becomes 0.5.
void normalise(double* v, std::size_t n)
{
    const auto [lo, hi] = std::minmax_element(v, v + n);
    const double mn = *lo;
    const double range = *hi - mn;
    if (!(range > 0.0)) {
        std::fill(v, v + n, 0.5);
        return;
    }
    // (x - mn) / range is exactly 0 at the minimum and exactly 1 (x / x) at the maximum.
    for (std::size_t i = 0; i < n; ++i) v[i] = (v[i] - mn) / range;
}

}  // namespace

std::vector<float> noiseMap(const NoiseMapSettings& s, const std::function<void()>& checkCancelled)
{
    if (s.nx < 1 || s.ny < 1) throw std::invalid_argument("noiseMap: nx and ny must be >= 1");
    if (!std::isfinite(s.beta) || s.beta < 0.0)
        throw std::invalid_argument("noiseMap: beta must be finite and >= 0");
    if (!(s.centreBias >= 0.0 && s.centreBias <= 1.0))
        throw std::invalid_argument("noiseMap: centreBias must be in [0, 1]");
    if (!(s.centreRadius > 0.0) || !std::isfinite(s.centreRadius))
        throw std::invalid_argument("noiseMap: centreRadius must be finite and > 0");
    if (!(s.largestWavelength >= 0.0) || !std::isfinite(s.largestWavelength))
        throw std::invalid_argument("noiseMap: largestWavelength must be finite and >= 0");

    const auto cancel = [&] {
        if (checkCancelled) checkCancelled();
    };
    const auto nx = static_cast<std::size_t>(s.nx);
    const auto ny = static_cast<std::size_t>(s.ny);
    const std::size_t n = nx * ny;
    const std::size_t nxc = nx / 2 + 1;  // complex columns of the r2c half spectrum
    const std::size_t nc = ny * nxc;

    RealBuffer real(static_cast<double*>(fftw_malloc(sizeof(double) * n)));
    ComplexBuffer spec(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * nc)));
    if (!real || !spec) throw std::bad_alloc();

    std::unique_ptr<Plan> forward, inverse;
    {
        // FFTW_ESTIMATE does not touch the arrays while planning, so planning before the
        // noise is written is fine. FFTW's 2D layout is row-major with n0 = ny, n1 = nx.
        std::lock_guard<std::mutex> lock(fftwPlannerMutex());
        fftw_plan f = fftw_plan_dft_r2c_2d(s.ny, s.nx, real.get(), spec.get(), FFTW_ESTIMATE);
        fftw_plan b = fftw_plan_dft_c2r_2d(s.ny, s.nx, spec.get(), real.get(), FFTW_ESTIMATE);
        // Plan's destructor takes the lock, so a failed pair is destroyed here, under it.
        if (!f || !b) {
            if (f) fftw_destroy_plan(f);
            if (b) fftw_destroy_plan(b);
            throw std::runtime_error("noiseMap: FFTW could not create a plan");
        }
        forward = std::make_unique<Plan>(f);
        inverse = std::make_unique<Plan>(b);
    }

    // 1. White Gaussian noise: Box-Muller on the counter RNG (1 - u is in (0, 1], log is finite).
    for (std::size_t i = 0; i < n; ++i) {
        if ((i % kCancelEvery) == 0) cancel();
        const double u1 = 1.0 - counterUniform(s.seed, kNoiseStream, 2 * i);
        const double u2 = counterUniform(s.seed, kNoiseStream, 2 * i + 1);
        real[i] = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
    }
    cancel();

    // 2. Forward FFT.
    forward->execute();
    cancel();

    // 3. Amplitude filter 1 / f^(beta/2): power 1 / f^beta. The r2c half spectrum holds
    //    kx = 0 .. nx/2; ky runs 0 .. ny-1 and is signed by wrapping the upper half.
    //    Frequencies under fMin (wavelengths over largestWavelength) are dropped.
    const double halfBeta = 0.5 * s.beta;
    const double fMin2 =
        s.largestWavelength > 0.0 ? 1.0 / (s.largestWavelength * s.largestWavelength) : 0.0;
    for (std::size_t j = 0; j < ny; ++j) {
        if ((j * nxc) % kCancelEvery < nxc) cancel();
        const double ky = (2 * j <= ny) ? double(j) : double(j) - double(ny);
        const double fy = ky / double(ny);
        for (std::size_t i = 0; i < nxc; ++i) {
            const double fx = double(i) / double(nx);
            const double f2 = fx * fx + fy * fy;
            // f^(-beta/2) = (f^2)^(-beta/4); the DC coefficient carries only the mean: drop it.
            const double gain = (f2 > 0.0 && f2 >= fMin2) ? std::pow(f2, -0.5 * halfBeta) : 0.0;
            fftw_complex& c = spec[j * nxc + i];
            c[0] *= gain;
            c[1] *= gain;
        }
    }
    cancel();

    // 4. Inverse FFT (unnormalised: a factor nx * ny that the min-max normalisation removes).
    inverse->execute();
    cancel();
    normalise(real.get(), n);

    // 5. Centre bias.
    if (s.centreBias > 0.0) {
        const double b = s.centreBias;
        const double cx = 0.5 * double(nx);
        const double cy = 0.5 * double(ny);
        const double radius = s.centreRadius * 0.5 * std::hypot(double(nx), double(ny));
        const double invR2 = 1.0 / (radius * radius);
        for (std::size_t iy = 0; iy < ny; ++iy) {
            if ((iy * nx) % kCancelEvery < nx) cancel();
            const double dy = double(iy) + 0.5 - cy;
            for (std::size_t ix = 0; ix < nx; ++ix) {
                const double dx = double(ix) + 0.5 - cx;
                const double g = std::exp(-(dx * dx + dy * dy) * invR2);
                real[iy * nx + ix] *= (1.0 - b) + b * g;
            }
        }
        normalise(real.get(), n);
    }

    cancel();
    std::vector<float> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<float>(real[i]);
    return out;
}

}  // namespace cg::algo
