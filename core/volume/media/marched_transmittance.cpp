#include "core/volume/media/marched_transmittance.hpp"

#include <algorithm>
#include <cmath>

namespace weft {

Vec3d marchedTransmittance(MediumRay& ray, double stepVoxels, std::int64_t& steps) {
    double indexPerWorld = 0;  // the finest volume's index units per world length along the ray
    for (const MediumSegment& s : ray.segments()) indexPerWorld = std::max(indexPerWorld, s.indexStep.length());
    if (!(indexPerWorld > 0)) return Vec3d(1.0);
    const double h = stepVoxels / indexPerWorld;
    Vec3d tau(0.0);
    for (double t = 0; t < ray.end();) {
        const MajorantSpan span = ray.majorantAt(t);
        if (span.majorant > 0) {
            const double n = std::ceil((span.next - t) / h), dt = (span.next - t) / n;
            for (double k = 0; k < n; ++k) tau += ray.at(t + (k + 0.5) * dt).extinction * dt;
            steps += std::int64_t(n);
            if (std::min({tau[0], tau[1], tau[2]}) > kOpaqueDepth) return Vec3d(0.0);
        }
        t = span.next;
    }
    return Vec3d(std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2]));
}

}  // namespace weft
