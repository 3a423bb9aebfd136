#include "algo/mapping/PrimitiveSubset.h"

#include <algorithm>

namespace cg::algo {

std::uint32_t subsetStride(std::uint64_t lastCount, std::uint64_t target)
{
    return static_cast<std::uint32_t>(
        std::max<std::uint64_t>(1, (lastCount + target - 1) / target));
}

void everyKthParticle(const std::vector<std::uint32_t>& counts, const std::vector<float>& positions,
                      std::uint32_t k, std::vector<std::uint32_t>& keptCounts,
                      std::vector<float>& keptPositions)
{
    keptCounts.clear();
    keptCounts.reserve(counts.size());
    std::uint64_t total = 0;
    for (std::uint32_t n : counts) {
        keptCounts.push_back((n + k - 1) / k);
        total += keptCounts.back();
    }
    keptPositions.clear();
    keptPositions.reserve(3 * total);
    std::size_t frameStart = 0;  // first float of the frame in `positions`
    for (std::uint32_t n : counts) {
        const float* frame = positions.data() + frameStart;
        for (std::uint32_t id = 0; id < n; id += k)
            keptPositions.insert(keptPositions.end(), frame + 3 * std::size_t{id},
                                 frame + 3 * std::size_t{id} + 3);
        frameStart += 3 * std::size_t{n};
    }
}

}  // namespace cg::algo
