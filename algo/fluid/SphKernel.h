#pragma once
/// The cubic B-spline SPH kernel in 3D (Monaghan 1992), written with the support radius H
/// (W = 0 for r >= H; H = 2 h in Monaghan's notation). Header-only: it sits in every inner loop.

#include <cmath>

namespace cg::algo {

class SphKernel {
public:
    /// `support` = H, metres (> 0).
    explicit SphKernel(double support)
        : mH(support),
          mInvH(1.0 / support),
          mSigma(8.0 / (3.14159265358979323846 * support * support * support))
    {
    }

    double support() const { return mH; }

    /// W(r), 1/m^3. Integrates to 1 over R^3.
    double value(double r) const
    {
        const double q = r * mInvH;
        if (q >= 1.0) return 0.0;
        if (q <= 0.5) return mSigma * (6.0 * (q * q * q - q * q) + 1.0);
        const double a = 1.0 - q;
        return mSigma * 2.0 * a * a * a;
    }

    /// dW/dr, 1/m^4 (<= 0).
    double derivative(double r) const
    {
        const double q = r * mInvH;
        if (q >= 1.0) return 0.0;
        if (q <= 0.5) return mSigma * mInvH * (18.0 * q * q - 12.0 * q);
        const double a = 1.0 - q;
        return -mSigma * mInvH * 6.0 * a * a;
    }

    /// grad W(x) for x = x_i - x_j with |x| = r, 1/m^4; writes `g`. Antisymmetric in x.
    void gradient(const double x[3], double r, double g[3]) const
    {
        const double s = r > 1e-12 * mH ? derivative(r) / r : 0.0;
        g[0] = s * x[0];
        g[1] = s * x[1];
        g[2] = s * x[2];
    }

private:
    double mH;
    double mInvH;
    double mSigma;
};

}  // namespace cg::algo
