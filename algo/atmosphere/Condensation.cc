#include "algo/atmosphere/Condensation.h"

#include <limits>
#include <stdexcept>

namespace cg::algo {

namespace {

template <typename Condenses>
CondensationState condenseWhere(const CondensationState* previous, const float* z,
                                std::size_t count, std::int32_t frame, Condenses condenses)
{
    CondensationState next;
    next.condensedFrame.assign(count, -1);
    next.condensedHeight.assign(count, std::numeric_limits<float>::quiet_NaN());
    if (previous) {
        if (previous->condensedFrame.size() != count || previous->condensedHeight.size() != count)
            throw std::invalid_argument("the particle count changed during the simulation");
        next.condensedFrame = previous->condensedFrame;
        next.condensedHeight = previous->condensedHeight;
        next.firstFrame = previous->firstFrame;
    }
    for (std::size_t i = 0; i < count; ++i) {
        if (next.condensedFrame[i] < 0 && condenses(i)) {
            next.condensedFrame[i] = frame;
            next.condensedHeight[i] = z[i];
        }
        if (next.condensedFrame[i] >= 0) ++next.count;
    }
    if (next.firstFrame < 0 && next.count > 0) next.firstFrame = frame;
    return next;
}

}  // namespace

CondensationState condenseStep(const CondensationState* previous, const float* temperature,
                               const float* z, std::size_t count, double dewPoint,
                               std::int32_t frame)
{
    return condenseWhere(previous, z, count, frame,
                         [&](std::size_t i) { return temperature[i] < dewPoint; });
}

CondensationState condenseStep(const CondensationState* previous, const float* temperature,
                               const float* dewpoints, const float* z, std::size_t count,
                               std::int32_t frame)
{
    return condenseWhere(previous, z, count, frame,
                         [&](std::size_t i) { return temperature[i] < dewpoints[i]; });
}

}  // namespace cg::algo
