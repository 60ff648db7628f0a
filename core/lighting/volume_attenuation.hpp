#pragma once
// Volumes as the deferred lighting techniques (lighting.vpl_deferred,
// lighting.adaptive_indirect) see them: a medium that absorbs and
// out-scatters the light along camera rays, shadow rays and light paths,
// by the deterministic marched transmittance (core/volume/media/
// marched_transmittance.hpp), and scatters none in. The medium is built
// only for a scene with volumes; without one active() is false and callers
// skip every lookup, so their images are exactly those of a mesh scene.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/base/options/params.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/media/marched_transmittance.hpp"

namespace weft {

struct GBuffer;

class VolumeAttenuation {
public:
    VolumeAttenuation(const Scene& scene, double stepVoxels);
    bool active() const { return medium_.has_value(); }
    const Medium& medium() const { return *medium_; }
    double stepVoxels() const { return step_; }

private:
    std::optional<Medium> medium_;  // only when some volume can attenuate
    double step_;
};

// The transmittance of straight segments, for one thread at a time (the
// medium's lookups keep per-thread accessors).
class SegmentAttenuation {
public:
    explicit SegmentAttenuation(const VolumeAttenuation& volumes);
    // From origin along the unit dir for distance (infinity: out of the scene).
    Vec3f along(const Vec3f& origin, const Vec3f& dir, float distance);
    // Adds volume.transmittance (segments marched), volume.steps and volume.lookups.
    void report(Counters& counters) const;

private:
    MediumRay ray_;
    double step_;
    std::int64_t segments_ = 0, steps_ = 0;
};

// Per texel, in image order: the transmittance from the eye to its surface
// (background texels: through the whole scene), along each pixel-centre
// ray of the G-buffer.
std::vector<Vec3f> cameraTransmittance(const Scene& scene, const GBuffer& g, const VolumeAttenuation& volumes,
                                       Counters& counters);

// Opacity of a pixel whose camera ray meets no surface: 1 - mean transmittance.
float backgroundAlpha(const Vec3f& transmittance);

// The `volume_step` parameter both techniques declare.
ParamSpec volumeStepParam();

}  // namespace weft
