#include "algo/atmosphere/Condensation.h"

#include <stdexcept>

namespace cg::algo {

namespace {

template <typename Condenses>
CondensationState condenseWhere(const CondensationState* previous, std::size_t count,
                                std::int32_t frame, Condenses condenses)
{
    CondensationState next;
    next.condensedFrame.assign(count, -1);
    if (previous) {
        if (previous->condensedFrame.size() != count)
            throw std::invalid_argument("the particle count changed during the simulation");
        next.condensedFrame = previous->condensedFrame;
        next.firstFrame = previous->firstFrame;
    }
    for (std::size_t i = 0; i < count; ++i) {
        if (next.condensedFrame[i] < 0 && condenses(i)) next.condensedFrame[i] = frame;
        if (next.condensedFrame[i] >= 0) ++next.count;
    }
    if (next.firstFrame < 0 && next.count > 0) next.firstFrame = frame;
    return next;
}

}  // namespace

CondensationState condenseStep(const CondensationState* previous, const float* temperature,
                               std::size_t count, double dewPoint, std::int32_t frame)
{
    return condenseWhere(previous, count, frame,
                         [&](std::size_t i) { return temperature[i] < dewPoint; });
}

CondensationState condenseStep(const CondensationState* previous, const float* temperature,
                               const float* dewpoints, std::size_t count, std::int32_t frame)
{
    return condenseWhere(previous, count, frame,
                         [&](std::size_t i) { return temperature[i] < dewpoints[i]; });
}

}  // namespace cg::algo
