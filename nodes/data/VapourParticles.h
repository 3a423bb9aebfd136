#pragma once
/// Water vapour particles of the stochastic simulation (Sec. 5.1), as structure-of-arrays.
/// What never changes after emission (id, home cell, start position, moisture) is shared by
/// every frame's state, so a simulation step writes only the arrays that move: height,
/// vertical velocity, temperature, and x, y once a wind or an outflow moves them.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/Data.h"

namespace cg {

class Registry;

/// Fixed at emission. Particle i has stable id[i] (ids are 0..N-1 in emission order).
struct VapourStatics {
    std::vector<std::uint32_t> id;
    std::vector<std::uint32_t> homeCell;  ///< map cell index iy * nx + ix (Eq. 16 reads it)
    std::vector<float> x;                 ///< metres, at emission
    std::vector<float> y;                 ///< metres, at emission
    std::vector<float> startZ;            ///< metres, P_vz(t0): where the particle's parcel starts
    /// Ours: each particle's own dew-point perturbation (C), for irregular cloud
    /// bases; empty when there is none.
    std::vector<float> dewpointOffset;
    /// Ours: seconds after t0 at which each particle leaves its start (a source that keeps
    /// feeding a tower); empty when all leave at t0, as in the paper.
    std::vector<float> releaseTime;

    std::size_t size() const { return id.size(); }
};

/// Particle state at one frame: P_vz, U_vz, T_v of Eq. 6-9.
class VapourParticlesData final : public Data {
public:
    VapourParticlesData(std::shared_ptr<const VapourStatics> statics, std::vector<float> z,
                        std::vector<float> vz, std::vector<float> temperature);
    /// With horizontal positions of their own (wind, outflow): `x` and `y` empty or size().
    VapourParticlesData(std::shared_ptr<const VapourStatics> statics, std::vector<float> x,
                        std::vector<float> y, std::vector<float> z, std::vector<float> vz,
                        std::vector<float> temperature);
    /// With the horizontal velocity of the step that moved them here as well (`vx`, `vy` empty
    /// or size()), for the motion of what rides on them (the mapper's copies).
    VapourParticlesData(std::shared_ptr<const VapourStatics> statics, std::vector<float> x,
                        std::vector<float> y, std::vector<float> vx, std::vector<float> vy,
                        std::vector<float> z, std::vector<float> vz,
                        std::vector<float> temperature);

    const std::shared_ptr<const VapourStatics> statics;
    const std::vector<float> z;            ///< height P_vz, metres
    const std::vector<float> vz;           ///< vertical velocity U_vz, m/s
    const std::vector<float> temperature;  ///< T_v, degrees Celsius

    std::size_t size() const { return z.size(); }
    /// The horizontal position at this frame: the emission's until something moved it.
    const std::vector<float>& xs() const { return mX.empty() ? statics->x : mX; }
    const std::vector<float>& ys() const { return mY.empty() ? statics->y : mY; }
    bool movedHorizontally() const { return !mX.empty(); }
    /// The horizontal velocity (m/s) of the step that brought each particle here (the wind at
    /// the height it came from, plus the outflow); empty where it is zero or unknown.
    const std::vector<float>& vxs() const { return mVx; }
    const std::vector<float>& vys() const { return mVy; }

    std::string typeName() const override { return "VapourParticles"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;
    static std::shared_ptr<const VapourParticlesData> deserialize(ByteReader& in);

private:
    std::vector<float> mX, mY;    ///< empty: statics->x, y
    std::vector<float> mVx, mVy;  ///< empty: zero
};

/// Which particles have become condensation particles (pseudocode lines 9-14).
class CondensationData final : public Data {
public:
    CondensationData(std::shared_ptr<const VapourParticlesData> particles,
                     std::vector<std::int32_t> condensedFrame, std::vector<float> condensedHeight,
                     std::int32_t firstFrame);

    /// The particles at this frame.
    const std::shared_ptr<const VapourParticlesData> particles;
    /// Frame at which particle i first had T_v < T_dp; -1 while it is still vapour.
    const std::vector<std::int32_t> condensedFrame;
    /// Height z of particle i at the frame it condensed (its condensation level); NaN while
    /// it is still vapour.
    const std::vector<float> condensedHeight;
    /// Frame at which the first condensation particle appeared (t_s[1]); -1 if none yet.
    const std::int32_t firstFrame;

    bool condensed(std::size_t i) const { return condensedFrame[i] >= 0; }
    std::size_t condensedCount() const;

    std::string typeName() const override { return "Condensation"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;
};

void registerVapourParticleTypes(Registry& registry);

}  // namespace cg
