#pragma once
// The scene's meshes in one Embree 3 BVH, built the first time a technique
// asks for it (scenes with volumes only never build one). Besides single
// rays it exposes Embree's ray streams (rtcIntersect1M / rtcOccluded1M) for
// coherent batches: primary rays of a tile, shadow rays from one VPL.
#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace weft {

struct SurfaceHit {
    float t = 0;
    std::uint32_t geom = RTC_INVALID_GEOMETRY_ID;
    std::uint32_t prim = 0;
    Vec3f normal;  // unit geometric normal on the side the winding faces
    bool valid() const { return geom != RTC_INVALID_GEOMETRY_ID; }
};

// Sets flush-to-zero and denormals-are-zero on the calling thread (Embree's
// advice for speed); cheap, so parallel bodies call it on entry.
void enableFastFloatMode();

class MeshAccel {
public:
    // Keeps its own copy of the meshes, so it never points into a moved scene.
    explicit MeshAccel(std::vector<TriangleMesh> meshes);
    ~MeshAccel();
    MeshAccel(const MeshAccel&) = delete;
    MeshAccel& operator=(const MeshAccel&) = delete;

    SurfaceHit intersect(const Vec3f& origin, const Vec3f& dir, float tnear, float tfar) const;
    // True when something lies between origin + tnear*dir and origin + tfar*dir.
    bool occluded(const Vec3f& origin, const Vec3f& dir, float tnear, float tfar) const;

    // Streams: hits/flags are written into the rays (Embree's conventions:
    // hit.geomID, ray.tfar = -inf when occluded).
    void intersectStream(RTCRayHit* rays, unsigned count, bool coherent) const;
    void occludedStream(RTCRay* rays, unsigned count, bool coherent) const;
    // A 16-ray packet (valid[i] = -1 for active lanes), for coherent rays such as a 4x4 pixel tile.
    void intersectPacket(const int* valid, RTCRayHit16& rays) const;

    // Unit geometric normal of a triangle (winding side).
    Vec3f normal(std::uint32_t geom, std::uint32_t prim) const;
    std::uint32_t material(std::uint32_t geom, std::uint32_t prim) const { return meshes_[geom].material[prim]; }
    const std::vector<TriangleMesh>& meshes() const { return meshes_; }

private:
    std::vector<TriangleMesh> meshes_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

// A ray stream entry ready for Embree.
inline void setRay(RTCRay& ray, const Vec3f& o, const Vec3f& d, float tnear, float tfar) {
    ray.org_x = o.x(), ray.org_y = o.y(), ray.org_z = o.z();
    ray.dir_x = d.x(), ray.dir_y = d.y(), ray.dir_z = d.z();
    ray.tnear = tnear, ray.tfar = tfar;
    ray.time = 0, ray.mask = 0xFFFFFFFFu, ray.id = 0, ray.flags = 0;
}

}  // namespace weft
