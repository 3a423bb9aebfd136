#pragma once
/// The 2D 1/f^beta density map fNoise(ix, iy) of Sec. 5.1 (pseudocode line 3: "Generate a
/// 2D 1/f^beta density map by the FFT method").
///
/// Method (spectral synthesis):
///  1. White Gaussian noise w(ix, iy): Box-Muller on two counter-based uniforms keyed by
///     (seed, cell index), so the map is a pure function of the settings.
///  2. Forward real-to-complex FFT (FFTW, double precision, single-threaded).
///  3. Each coefficient is scaled by 1 / f^(beta/2), so the power spectrum falls as 1/f^beta,
///     with f = sqrt((kx/nx)^2 + (ky/ny)^2) in cycles per cell and kx, ky the signed
///     frequency indices. Frequencies are in cycles per cell on both axes, so a non-square
///     map has an isotropic spectrum on the ground. The DC coefficient is set to 0, and
///     so is every coefficient with a wavelength 1/f longer than `largestWavelength` cells
///     when that is > 0 (ours, not the paper's: a cumulus field has a spacing).
///  4. Inverse FFT, then min-max normalisation to [0, 1]: the smallest cell is exactly 0 and
///     the largest exactly 1. A constant field (only a 1x1 map) becomes 0.5 everywhere.
///  5. Optional centre bias (Figure 6: "high density at the center"), applied to the
///     normalised map v:  v' = v * ((1 - b) + b * exp(-(r / R)^2)), with r the distance in
///     cells from the cell centre (ix + 0.5, iy + 0.5) to the map centre (nx / 2, ny / 2) and
///     R = centreRadius * half-diagonal (0.5 * sqrt(nx^2 + ny^2) cells); then v' is
///     normalised to [0, 1] again. With b = 0 this step is skipped: the pure 1/f^beta map.
///
/// The result is bitwise identical for any thread count: no FFTW threads are used and the
/// noise does not depend on evaluation order. (It assumes nobody in the process loads FFTW
/// wisdom, which could change the plan FFTW_ESTIMATE picks and so the rounding.)

#include <cstdint>
#include <functional>
#include <vector>

namespace cg::algo {

struct NoiseMapSettings {
    int nx = 64;                ///< cells along x, >= 1
    int ny = 64;                ///< cells along y, >= 1
    double beta = 3.0;          ///< spectral exponent: power ~ 1/f^beta; >= 0, finite
    std::uint64_t seed = 0;     ///< white-noise seed
    double centreBias = 0.0;    ///< b in [0, 1]: 0 = pure noise, 1 = full Gaussian falloff
    double centreRadius = 0.5;  ///< R as a fraction of the half-diagonal, > 0
    /// Wavelengths longer than this many cells are removed; 0 keeps them all (the paper).
    /// A pure 1/f^beta map puts most of its power in its largest scale, which gathers the
    /// dense cells into one or two regions; without it the dense cells form separate
    /// patches about half this wavelength across, like the cells of a cumulus field.
    double largestWavelength = 0.0;
};

/// Returns nx * ny values in [0, 1], row-major (index = iy * nx + ix), min exactly 0 and max
/// exactly 1 (unless nx = ny = 1). `checkCancelled` is called every so often and may throw
/// to abandon the computation (nothing leaks). Throws std::invalid_argument for bad settings.
std::vector<float> noiseMap(const NoiseMapSettings& settings,
                            const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
