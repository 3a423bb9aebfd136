#include "algo/atmosphere/HeroClouds.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cg::algo {

std::vector<HeroCloud> heroCloudsFromList(const std::vector<double>& v)
{
    if (v.size() % kNumbersPerHeroCloud != 0)
        throw std::invalid_argument("heroClouds holds " + std::to_string(v.size()) +
                                    " numbers; each hero is 4: x, y, radius, start");
    std::vector<HeroCloud> heroes;
    for (std::size_t i = 0; i < v.size(); i += kNumbersPerHeroCloud) {
        const std::string which = "hero cloud " + std::to_string(i / kNumbersPerHeroCloud);
        for (std::size_t k = 0; k < kNumbersPerHeroCloud; ++k)
            if (!std::isfinite(v[i + k]))
                throw std::invalid_argument(which + ": a value is not finite");
        const HeroCloud h{v[i], v[i + 1], v[i + 2], v[i + 3]};
        if (!(h.radius > 0.0)) throw std::invalid_argument(which + ": its radius must be > 0");
        if (h.start < 0.0) throw std::invalid_argument(which + ": its start must be >= 0 s");
        heroes.push_back(h);
    }
    return heroes;
}

double heroDensity(double r, double radius)
{
    const double t = std::clamp((radius - r) / (0.5 * radius), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

std::vector<std::int32_t> stampHeroClouds(int nx, int ny, double cell, std::vector<float>& values,
                                          const std::vector<HeroCloud>& heroes)
{
    std::vector<std::int32_t> owner(values.size(), -1);
    for (std::size_t h = 0; h < heroes.size(); ++h) {
        const HeroCloud& hero = heroes[h];
        // Only the cells the disk can reach.
        const int x0 = std::max(0, static_cast<int>(std::floor((hero.x - hero.radius) / cell)));
        const int x1 =
            std::min(nx - 1, static_cast<int>(std::floor((hero.x + hero.radius) / cell)));
        const int y0 = std::max(0, static_cast<int>(std::floor((hero.y - hero.radius) / cell)));
        const int y1 =
            std::min(ny - 1, static_cast<int>(std::floor((hero.y + hero.radius) / cell)));
        for (int iy = y0; iy <= y1; ++iy)
            for (int ix = x0; ix <= x1; ++ix) {
                const double r = std::hypot((ix + 0.5) * cell - hero.x, (iy + 0.5) * cell - hero.y);
                const auto d = static_cast<float>(heroDensity(r, hero.radius));
                const std::size_t i = static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) +
                                      static_cast<std::size_t>(ix);
                if (d > values[i]) {
                    values[i] = d;
                    owner[i] = static_cast<std::int32_t>(h);
                }
            }
    }
    return owner;
}

}  // namespace cg::algo
