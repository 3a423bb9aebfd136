#pragma once
/// Checks shared by the deserializers of the port data types. A disk cache entry can be
/// forged with valid checksums, so a deserializer refuses any bytes that would build a value
/// its consumers could not trust; every refusal is a std::runtime_error naming the type, which
/// the disk cache turns into a miss to recook.

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/Data.h"

namespace cg::checks {

/// Frame numbers a stored value may hold: far beyond any graph's (0..1,000,000), small enough
/// that frame arithmetic in the consumers (t - t0, t_s + chi L) cannot overflow an int.
inline constexpr std::int64_t kMaxFrame = std::int64_t{1} << 30;

[[noreturn]] inline void refuse(const char* type, const std::string& why)
{
    throw std::runtime_error(std::string(type) + ": " + why);
}

/// A stored u64 that must lie in [lo, hi] as a signed integer (the writers store signed
/// values as two's complement); refused rather than truncated to its field.
inline std::int64_t intIn(std::uint64_t stored, std::int64_t lo, std::int64_t hi, const char* type,
                          const char* what)
{
    const auto v = static_cast<std::int64_t>(stored);
    if (v < lo || v > hi)
        refuse(type, std::string(what) + " " + std::to_string(v) + " is outside [" +
                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
}

/// A stored u64 that must be at most `hi`.
inline std::uint64_t uintUpTo(std::uint64_t v, std::uint64_t hi, const char* type, const char* what)
{
    if (v > hi)
        refuse(type,
               std::string(what) + " " + std::to_string(v) + " is above " + std::to_string(hi));
    return v;
}

/// A number that must be finite and in [lo, hi] (NaN fails every comparison).
inline double finiteIn(double v, double lo, double hi, const char* type, const char* what)
{
    if (!(v >= lo && v <= hi) || !std::isfinite(v))
        refuse(type, std::string(what) + " " + std::to_string(v) + " is not a finite number in [" +
                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
}

/// A stored f64 that must be a float exactly (the writers widen floats), finite, in [lo, hi].
inline float floatIn(double v, double lo, double hi, const char* type, const char* what)
{
    finiteIn(v, lo, hi, type, what);
    const auto f = static_cast<float>(v);
    if (static_cast<double>(f) != v)
        refuse(type, std::string(what) + " " + std::to_string(v) + " is not a 32-bit float");
    return f;
}

}  // namespace cg::checks
