#pragma once
/// Sizes formed as products of extents (voxels, blocks or cells per axis), in overflow-checked
/// 64-bit arithmetic. A product that wraps is small: it passes every size check made after
/// it, and the storage it sizes is then indexed by the full extents, past its end.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>

namespace cg::util {

/// a * b, or nothing when the product exceeds 2^64 - 1.
constexpr std::optional<std::uint64_t> checkedMul(std::uint64_t a, std::uint64_t b)
{
    std::uint64_t product = 0;
    if (__builtin_mul_overflow(a, b, &product)) return std::nullopt;
    return product;
}

/// The product of `extents` (1 for none), or nothing when an extent is negative or the product
/// exceeds 2^64 - 1.
constexpr std::optional<std::uint64_t> checkedProduct(std::initializer_list<std::int64_t> extents)
{
    std::uint64_t product = 1;
    for (const std::int64_t e : extents) {
        if (e < 0) return std::nullopt;
        const std::optional<std::uint64_t> next =
            checkedMul(product, static_cast<std::uint64_t>(e));
        if (!next) return std::nullopt;
        product = *next;
    }
    return product;
}

/// The product of `extents` when it is at most `limit`, else nothing (also when it overflows
/// or an extent is negative): the size check and the product in one step, so that no caller
/// compares a wrapped product against its limit.
constexpr std::optional<std::uint64_t> productWithin(std::initializer_list<std::int64_t> extents,
                                                     std::uint64_t limit)
{
    const std::optional<std::uint64_t> product = checkedProduct(extents);
    if (!product || *product > limit) return std::nullopt;
    return product;
}

/// "a x b x c", the extents of a size for a message: unlike their product, they never wrap.
inline std::string extentsText(std::initializer_list<std::int64_t> extents)
{
    std::string text;
    for (const std::int64_t e : extents) text += (text.empty() ? "" : " x ") + std::to_string(e);
    return text;
}

}  // namespace cg::util
