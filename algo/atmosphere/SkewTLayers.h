#pragma once
/// The skew-T diagram's layers, drawn by drawSkewT (SkewT.h) in this order: the shaded CAPE and
/// CIN, the reference lines and axes (SkewTBackground.cc), the sounding, the parcel and its
/// levels (SkewTSounding.cc), the wind barbs (SkewTWind.cc), then the title and legend.

#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Profile.h"
#include "algo/atmosphere/SkewT.h"
#include "algo/atmosphere/SkewTCanvas.h"

namespace cg::algo::skewt {

/// Isotherms every 10 C, labelled on the temperature axis below the plot and where they leave
/// its top edge; the 0 C isotherm darker.
void drawIsotherms(SkewTCanvas& canvas, const SkewTAxes& a);
/// Isobars every 100 hPa, labelled on the left.
void drawIsobars(SkewTCanvas& canvas, const SkewTAxes& a);
/// Dry adiabats every 10 K of potential temperature: T = theta (p / 1000)^(R_d / c_pd).
void drawDryAdiabats(SkewTCanvas& canvas, const SkewTAxes& a);
/// Saturated adiabats through 1000 hPa every 5 C, up to 200 hPa.
void drawMoistAdiabats(SkewTCanvas& canvas, const SkewTAxes& a);
/// Lines of constant saturation mixing ratio (dashed) up to 600 hPa, labelled in g/kg.
void drawMixingRatioLines(SkewTCanvas& canvas, const SkewTAxes& a);

/// The temperature (C) of a saturated parcel at `hPa` that had `t1000` C at 1000 hPa: the
/// moist adiabatic lapse integrated in pressure (dT/dp = Gamma_m R_d T / (g p)), midpoint rule.
double moistAdiabatTemperature(double t1000, double hPa);

/// The CAPE (parcel warmer than the environment between the LFC and the EL) in translucent
/// red and the CIN (parcel colder, below the LFC) in translucent blue; nothing without an LFC.
void shadeBuoyancy(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile,
                   const ParcelAscent& parcel);
/// The environment's temperature and dew point and the parcel's path.
void drawSoundingCurves(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile,
                        const ParcelAscent& parcel);
/// LCL, LFC and EL as ticks on the plot's right edge labelled with name and pressure (labels
/// pushed apart where levels crowd); the options' cloud as a bar beside them.
void drawParcelLevels(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile,
                      const ParcelAscent& parcel);

/// Wind barbs right of the plot, one about every 24 pixels of height from the ground to the
/// profile's top, where the wind rounds to at least 5 knots.
void drawWindBarbs(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile);
/// One barb: its staff from `base` toward where the wind blows from, `length` pixels, with a
/// pennant per 50 knots, a barb per 10 and a half barb per 5 (rounded to 5 knots) on its
/// clockwise side. Nothing for calm air (under 2.5 knots).
void drawWindBarb(SkewTCanvas& canvas, SkewTPoint base, Wind wind, double length = 24.0);

}  // namespace cg::algo::skewt
