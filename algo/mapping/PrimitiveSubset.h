#pragma once
/// Every k-th particle of a primitive set (see docs/mapper.md, "A caution on counts"). No
/// engine includes.

#include <cstdint>
#include <vector>

namespace cg::algo {

/// The stride k = ceil(lastCount / target), at least 1, that leaves about `target` particles
/// at the last frame (`lastCount` = N_f(last)).
std::uint32_t subsetStride(std::uint64_t lastCount, std::uint64_t target);

/// Keeps ids 0, k, 2k, ... of a primitive set given as per-frame counts and positions (the
/// layout of PrimitiveSetData). Ids appear in order, so frame s keeps ceil(N_f(s) / k)
/// particles and the subset is again a primitive set (stable ids in order of appearance,
/// N_f non-decreasing); each kept particle follows its physical trajectory. `k` >= 1.
void everyKthParticle(const std::vector<std::uint32_t>& counts, const std::vector<float>& positions,
                      std::uint32_t k, std::vector<std::uint32_t>& keptCounts,
                      std::vector<float>& keptPositions);

}  // namespace cg::algo
