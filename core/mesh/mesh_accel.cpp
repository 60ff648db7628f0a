#include "core/mesh/mesh_accel.hpp"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <limits>

#include "core/base/error.hpp"

namespace weft {

void enableFastFloatMode() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

namespace {

void attachMesh(RTCDevice device, RTCScene scene, const TriangleMesh& mesh) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        v[3 * i] = mesh.positions[i].x(), v[3 * i + 1] = mesh.positions[i].y(), v[3 * i + 2] = mesh.positions[i].z();
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.triangleCount()));
    std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
}

}  // namespace

MeshAccel::MeshAccel(std::vector<TriangleMesh> meshes) : meshes_(std::move(meshes)) {
    device_ = rtcNewDevice("verbose=0");
    if (!device_) throw Error("Embree: cannot create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    for (const TriangleMesh& m : meshes_) attachMesh(device_, scene_, m);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw Error("Embree: building the BVH failed");
}

MeshAccel::~MeshAccel() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

SurfaceHit MeshAccel::intersect(const Vec3f& o, const Vec3f& d, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    setRay(rh.ray, o, d, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    SurfaceHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.t = rh.ray.tfar, hit.geom = rh.hit.geomID, hit.prim = rh.hit.primID;
    hit.normal = normal(hit.geom, hit.prim);
    return hit;
}

bool MeshAccel::occluded(const Vec3f& o, const Vec3f& d, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    setRay(ray, o, d, tnear, tfar);
    rtcOccluded1(scene_, &ctx, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

void MeshAccel::intersectStream(RTCRayHit* rays, unsigned count, bool coherent) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(scene_, &ctx, rays, count, sizeof(RTCRayHit));
}

void MeshAccel::occludedStream(RTCRay* rays, unsigned count, bool coherent) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded1M(scene_, &ctx, rays, count, sizeof(RTCRay));
}

void MeshAccel::intersectPacket(const int* valid, RTCRayHit16& rays) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(valid, scene_, &ctx, &rays);
}

Vec3f MeshAccel::normal(std::uint32_t geom, std::uint32_t prim) const {
    const TriangleMesh& m = meshes_[geom];
    const Vec3f& a = m.positions[m.indices[3 * prim]];
    const Vec3f& b = m.positions[m.indices[3 * prim + 1]];
    const Vec3f& c = m.positions[m.indices[3 * prim + 2]];
    Vec3f n = (b - a).cross(c - a);
    const float len = n.length();
    return len > 0 ? n / len : Vec3f(0, 1, 0);
}

}  // namespace weft
