#include "core/lighting/volume_attenuation.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/lighting/direct_light.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/screen/gbuffer.hpp"

namespace weft {

namespace {

const Counter kVolumeTransmittance{"volume.transmittance", "segments whose volume transmittance was marched (camera, shadow and VPL rays)"};
const Counter kVolumeSteps{"volume.steps", "midpoint steps of those transmittance marches"};

}  // namespace

namespace {

bool attenuates(const Volume& v) {
    const Vec3d sigma = v.medium.absorb + v.medium.scatter;
    return !v.empty() && std::max({sigma[0], sigma[1], sigma[2]}) > 0;
}

}  // namespace

VolumeAttenuation::VolumeAttenuation(const Scene& scene, double stepVoxels) : step_(stepVoxels) {
    if (std::any_of(scene.volumes.begin(), scene.volumes.end(), attenuates)) medium_.emplace(scene.volumes);
}

SegmentAttenuation::SegmentAttenuation(const VolumeAttenuation& volumes) : ray_(volumes.medium()), step_(volumes.stepVoxels()) {}

Vec3f SegmentAttenuation::along(const Vec3f& origin, const Vec3f& dir, float distance) {
    ++segments_;
    ray_.reset(toVec3d(origin), toVec3d(dir), std::isfinite(distance) ? double(distance) : std::numeric_limits<double>::infinity());
    if (ray_.empty()) return Vec3f(1, 1, 1);
    return toVec3f(marchedTransmittance(ray_, step_, steps_));
}

Vec3f attenuated(SegmentAttenuation& media, const Vec3f& light, const Vec3f& origin, const Vec3f& dir, float distance) {
    return light * media.along(origin, dir, distance);
}

void SegmentAttenuation::report(Counters& counters) const {
    counters.add(kVolumeTransmittance, segments_);
    counters.add(kVolumeSteps, steps_);
    counters.add(kVolumeLookups, ray_.lookups);
}

std::vector<Vec3f> cameraTransmittance(const Scene& scene, const GBuffer& g, const VolumeAttenuation& volumes,
                                       Counters& counters) {
    std::vector<Vec3f> out(g.texels.size(), Vec3f(1, 1, 1));
    const Vec3f eye = toVec3f(scene.camera.eye);
    tbb::parallel_for(0, g.height, [&](int y) {
        enableFastFloatMode();
        SegmentAttenuation segment(volumes);
        for (int x = 0; x < g.width; ++x) {
            const GTexel& t = g.at(x, y);
            Vec3f dir;
            float distance = std::numeric_limits<float>::infinity();
            if (t.background()) {
                dir = toVec3f(scene.camera.generate(x + 0.5, y + 0.5, g.width, g.height).dir);
            } else {
                dir = (t.position - eye).unitSafe(), distance = t.depth;
            }
            out[std::size_t(y) * g.width + x] = segment.along(eye, dir, distance);
        }
        segment.report(counters);
    });
    return out;
}

float backgroundAlpha(const Vec3f& T) { return std::clamp(1.0f - (T.x() + T.y() + T.z()) / 3.0f, 0.0f, 1.0f); }

ParamSpec volumeStepParam() {
    return floatParam("volume_step", 1.0, 0.01, 64,
                      "transmittance through volumes: midpoint steps of at most this many voxel lengths (scenes with volumes only)");
}

}  // namespace weft
