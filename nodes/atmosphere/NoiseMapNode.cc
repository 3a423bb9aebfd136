// NoiseMap: the 2D 1/f^beta density map fNoise(ix, iy) of Sec. 5.1 (pseudocode line 3).

#include <cstdint>
#include <memory>
#include <vector>

#include "algo/atmosphere/NoiseMap.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/Map2D.h"

namespace cg {

namespace {

// Peak memory per cell: the real FFT buffer (double), the half-size complex spectrum
// (counted as a full 16 bytes to stay conservative) and the float output.
constexpr std::uint64_t kBytesPerCell = sizeof(double) + 2 * sizeof(double) + sizeof(float);

class NoiseMapNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        algo::NoiseMapSettings s;
        s.nx = static_cast<int>(p.getInt("width"));
        s.ny = static_cast<int>(p.getInt("height"));
        s.beta = p.getFloat("beta");
        s.seed = static_cast<std::uint64_t>(p.getInt("seed"));
        s.centreBias = p.getFloat("centreBias");
        s.centreRadius = p.getFloat("centreRadius");
        s.largestWavelength = p.getFloat("largestWavelength");
        std::vector<float> values = algo::noiseMap(s, [&ctx] { ctx.checkCancelled(); });
        ctx.setOutput("map", std::make_shared<Map2DData>(s.nx, s.ny, p.getFloat("cellSize"),
                                                         std::move(values)));
    }
};

}  // namespace

void registerNoiseMapNode(Registry& registry)
{
    NodeDecl d;
    d.type = "NoiseMap";
    d.version = 1;
    d.category = "atmosphere";
    d.doc =
        "The 2D 1/f^beta density map fNoise(ix, iy) of Sec. 5.1 (Eqs. 3-4; pseudocode line 3, "
        "\"by the FFT method\"): white Gaussian noise keyed by seed and cell, filtered in "
        "Fourier space by 1/f^(beta/2) so its power spectrum falls as 1/f^beta (f in cycles per "
        "cell on both axes, so non-square maps stay isotropic; mean removed), then normalised "
        "to exactly [0, 1]. An optional centre bias (ours, for Figure 6's \"high density at the "
        "center\") multiplies the map by (1 - b) + b exp(-(r/R)^2) and normalises again. "
        "Also ours: largestWavelength drops the scales longer than it, so the dense cells form "
        "separate patches (a cumulus field's spacing) instead of one or two continents. "
        "Frame-independent: cooks once per animation; identical for any thread count.";
    d.outputs = {port("map", "Map2D",
                      "fNoise(ix, iy) in [0, 1] (min 0, max 1), row iy = 0 at the ground's y = 0")};
    d.params = {
        intParam("width", 64, "cells",
                 "nx, cells along x (paper: 64x64 in Fig. 6, 150x100, 200x100, 300x100)", 1, 65536),
        intParam("height", 64, "cells", "ny, cells along y", 1, 65536),
        floatParam("beta", 3.0, "",
                   "spectral exponent beta of 1/f^beta (paper uses 2.7, 3.0, 3.3; 3.0 as in "
                   "Fig. 8); larger is smoother",
                   0.0, 6.0),
        intParam("seed", 0, "", "white-noise seed", 0),
        floatParam("cellSize", 50.0, "m",
                   "edge of one grid cell (ours: the paper gives none; 64 cells cover 3.2 km)",
                   1e-3, 1e6),
        floatParam("centreBias", 0.0, "",
                   "b: 0 = pure 1/f^beta map, 1 = fully weighted by the central Gaussian (ours, "
                   "for Fig. 6)",
                   0.0, 1.0),
        floatParam("centreRadius", 0.5, "",
                   "R of the centre Gaussian as a fraction of the half-diagonal (ours)", 0.01,
                   10.0),
        floatParam("largestWavelength", 0.0, "cells",
                   "ours: Fourier components with a longer wavelength are removed, so dense "
                   "patches are about half of it across and spaced about it apart (a cumulus "
                   "field's spacing, a few boundary-layer depths); 0 keeps every scale (the "
                   "paper)",
                   0.0, 1e6)};
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        check.checkAllocation("width", {p.getInt("width"), p.getInt("height")}, kBytesPerCell);
    };
    d.create = [] { return std::make_unique<NoiseMapNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
