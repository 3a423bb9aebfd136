#include "algo/volume/LeafFromDense.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace cg::algo {

using LeafT = openvdb::FloatTree::LeafNodeType;
static_assert(LeafT::LOG2DIM == 3, "a leaf is 8^3 voxels");

std::unique_ptr<LeafT> leafFromDense(const float* first, std::ptrdiff_t xStride,
                                     std::ptrdiff_t yStride, const openvdb::Coord& leafOrigin,
                                     bool clamp)
{
    // Eight voxels along z at a time (SSE2): the mask bits of a row come from one movemask.
    // Voxel (x, y, z) is bit 8 y + z of the mask's word x.
    // Elsewhere a scalar loop gives the same bits.
    LeafT::NodeMaskType mask;
    alignas(64) float values[LeafT::SIZE];
#if defined(__SSE2__)
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
#endif
    for (int x = 0; x < 8; ++x) {
        std::uint64_t word = 0;
        for (int y = 0; y < 8; ++y) {
            const float* row = first + x * xStride + y * yStride;
            float* out = values + (x << 6) + (y << 3);
#if defined(__SSE2__)
            for (int h = 0; h < 2; ++h) {
                __m128 v = _mm_loadu_ps(row + 4 * h);
                const __m128 on = _mm_cmpgt_ps(v, zero);  // false for NaN
                if (clamp) v = _mm_min_ps(v, one);
                _mm_storeu_ps(out + 4 * h, _mm_and_ps(on, v));
                word |= std::uint64_t(_mm_movemask_ps(on)) << (8 * y + 4 * h);
            }
#else
            for (int z = 0; z < 8; ++z) {
                const bool on = row[z] > 0.0f;  // false for NaN
                out[z] = on ? (clamp ? std::min(row[z], 1.0f) : row[z]) : 0.0f;
                word |= std::uint64_t(on) << (8 * y + z);
            }
#endif
        }
        mask.template getWord<std::uint64_t>(static_cast<openvdb::Index>(x)) = word;
    }
    if (mask.isOff()) return nullptr;
    auto leaf = std::make_unique<LeafT>(leafOrigin, 0.0f, false);
    std::memcpy(leaf->buffer().data(), values, sizeof(values));
    leaf->setValueMask(mask);
    return leaf;
}

}  // namespace cg::algo
