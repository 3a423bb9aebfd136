#!/usr/bin/env python3
"""Writes the shipped sounding files (graphs/soundings/) in both formats, University of Wyoming
text list and CSV, from the made-up profiles below. They are ours, not observations: a
fair-weather cumulus day (LCL near 1.2 km above sea level, an inversion near 2.5 km) and a
deep-convection day (LCL near 1 km above the ground, equilibrium level near 11.5 km, moderate
shear). Run it from the checkout's root: python3 scripts/make_soundings.py"""
import math

KNOT = 0.514444  # m/s
EPS, RD, G = 0.622, 287.053, 9.80665


def e_s(t):  # Bolton 1980, hPa
    return 6.112 * math.exp(17.67 * t / (t + 243.5))


def mixr(td, p):  # g/kg
    e = e_s(td)
    return 1000 * EPS * e / (p - e)


def theta(t, p):
    return (t + 273.15) * (1000.0 / p) ** 0.2857


def theta_e(t, td, p):  # Bolton's approximation (eq. 43), K
    r = mixr(td, p)
    tk, tdk = t + 273.15, td + 273.15
    tl = 1 / (1 / (tdk - 56) + math.log(tk / tdk) / 800) + 56
    return tk * (1000 / p) ** (0.2854 * (1 - 0.28e-3 * r)) * math.exp((3.376 / tl - 0.00254) * r * (1 + 0.81e-3 * r))


def levels(ground_m, ground_hpa, rows):
    """rows: (height m, T C, Td C or None, wind from deg, speed knots); pressure hydrostatic."""
    out, p, prev = [], ground_hpa, None
    for z, t, td, d, s in rows:
        if prev is not None:
            tm = 0.5 * (t + prev[1]) + 273.15
            p = p * math.exp(-G * (z - prev[0]) / (RD * tm))
        out.append((round(p, 1), z, t, td, d, s))
        prev = (z, t)
    return out


def wyoming(title, rows):
    lines = ["<HTML>", "<TITLE>University of Wyoming - Radiosonde Data</TITLE>", '<BODY BGCOLOR="white">',
             f"<H2>{title}</H2>", "<PRE>", "-" * 77,
             "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV",
             "    hPa      m      C      C      %   g/kg    deg   knot      K      K      K ", "-" * 77]
    for p, z, t, td, d, s in rows:
        f = [f"{p:7.1f}", f"{z:7d}", f"{t:7.1f}"]
        if td is None:
            f += [" " * 7] * 3
        else:
            rh = 100 * e_s(td) / e_s(t)
            f += [f"{td:7.1f}", f"{rh:7.0f}", f"{mixr(td, p):7.2f}"]
        f += [f"{d:7d}", f"{s:7d}", f"{theta(t, p):7.1f}"]
        f += [" " * 7 if td is None else f"{theta_e(t, td, p):7.1f}"]
        r = 0 if td is None else mixr(td, p) / 1000
        f += [f"{theta(t, p) * (1 + 0.61 * r):7.1f}"]
        lines.append("".join(f))
    lines += ["</PRE><H3>Station information and sounding indices</H3><PRE>",
              "                         Station number: 99999", "</PRE>"]
    return "\n".join(lines) + "\n"


def csv(comment, rows):
    lines = [f"# {comment}", "height_m,temperature_C,dewpoint_C,pressure_hPa,wind_dir_deg,wind_speed_ms"]
    for p, z, t, td, d, s in rows:
        lines.append(f"{z},{t},{'' if td is None else td},{p},{d},{s * KNOT:.3f}")
    return "\n".join(lines) + "\n"


# Fair weather: a moist mixed layer under a subsidence inversion (9.2 C at 2.0 km, 11.0 C at
# 2.5 km) and a free troposphere above it that is stable for a parcel lifted from the cloud
# base (its saturated equivalent potential temperature, 336-340 K, above the parcel's 333 K at
# every level), so the thermals stop at the inversion.
FAIR = levels(180, 990.0, [
    (180, 24.0, 16.0, 200, 6), (530, 20.4, 14.8, 210, 8), (758, 18.2, 14.0, 215, 10),
    (992, 16.0, 13.2, 220, 12), (1475, 12.6, 10.6, 230, 14), (1980, 9.2, 3.2, 240, 16),
    (2510, 11.0, -9.4, 245, 18), (3070, 8.0, -12.4, 250, 20), (5760, -8.0, -29.9, 260, 28),
    (9420, -36.0, None, 270, 40), (11950, -53.0, None, 270, 45)])

# Deep convection: a moist boundary layer (30 C over 22 C: LCL ~1 km above the ground), a
# conditionally unstable troposphere (~6.8 C/km), the tropopause at 11.5 km; the wind veers and
# strengthens from 5 knots from the south to 50 knots from the west-southwest (moderate shear).
DEEP = levels(200, 985.0, [
    (200, 30.0, 22.0, 170, 10), (500, 27.3, 21.4, 185, 12), (1000, 22.8, 20.0, 200, 15),
    (1500, 19.0, 16.0, 215, 18), (2000, 15.7, 11.5, 225, 21), (3000, 9.0, 2.0, 235, 26),
    (4000, 2.6, -6.0, 240, 30), (5000, -3.6, -14.0, 245, 34), (6000, -9.8, -21.0, 245, 38),
    (7000, -16.0, -29.0, 250, 42), (8000, -22.4, -37.0, 250, 45), (9000, -28.8, -45.0, 250, 47),
    (10000, -35.2, -52.0, 255, 49), (11000, -40.6, -58.0, 255, 50), (11500, -42.8, -61.0, 255, 50),
    (12500, -43.5, None, 260, 45), (14500, -44.0, None, 260, 38), (16500, -43.0, None, 265, 30)])

if __name__ == "__main__":
    files = {
        "graphs/soundings/fair_weather.txt": wyoming("99999 CGFW CloudGraph fair-weather cumulus day (made up) 12Z 01 Jul 2026", FAIR),
        "graphs/soundings/fair_weather.csv": csv("CloudGraph fair-weather cumulus day (made up): the levels of fair_weather.txt", FAIR),
        "graphs/soundings/deep_convection.txt": wyoming("99999 CGDC CloudGraph deep-convection day (made up) 18Z 15 Jul 2026", DEEP),
        "graphs/soundings/deep_convection.csv": csv("CloudGraph deep-convection day (made up): the levels of deep_convection.txt", DEEP),
    }
    for path, text in files.items():
        with open(path, "w") as f:
            f.write(text)
