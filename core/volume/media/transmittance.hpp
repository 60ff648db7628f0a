#pragma once
// Transmittance along a ray through a heterogeneous medium, three ways:
//   marchTransmittance  fixed-step quadrature (vdb_render's shadow rays)
//   ratioTracking       unbiased: tentative collisions drawn against a
//                       majorant, each weighted by 1 - sigma / majorant
//                       (Novak et al. 2014); noise instead of step bias
// The medium is a callable sigma(t) -> Vec3 extinction per unit length at
// distance t along the ray (RGB, so each channel may differ).
#include <algorithm>
#include <cmath>

#include "core/scene/camera.hpp"
#include "core/base/rng.hpp"

namespace weft {

// vdb_render's shadow-ray rule: samples at step * ceil(t0 / step) + k * step
// up to t1 (inclusive), each multiplying exp(-sigma * step); the march stops
// once |T|^2 < cutoff.
template <class Sigma>
Vec3d marchTransmittance(const Sigma& sigma, double t0, double t1, double step, double cutoff, Vec3d T = Vec3d(1.0)) {
    for (double t = step * std::ceil(t0 / step); t <= t1; t += step) {
        const Vec3d s = sigma(t);
        T *= Vec3d(std::exp(-s[0] * step), std::exp(-s[1] * step), std::exp(-s[2] * step));
        if (T.lengthSqr() < cutoff) break;
    }
    return T;
}

// Ratio tracking over [t0, t1] against a majorant >= every channel of
// sigma; rng supplies the free paths. Unbiased for any majorant that bounds.
template <class Sigma>
Vec3d ratioTracking(const Sigma& sigma, double t0, double t1, double majorant, Rng& rng) {
    Vec3d T(1.0);
    if (!(majorant > 0)) return T;
    for (double t = t0;;) {
        t -= std::log1p(-rng.uniformDouble()) / majorant;
        if (t >= t1) return T;
        const Vec3d s = sigma(t);
        for (int c = 0; c < 3; ++c) T[c] *= std::clamp(1.0 - s[c] / majorant, 0.0, 1.0);
        if (T[0] + T[1] + T[2] == 0.0) return T;
    }
}

}  // namespace weft
