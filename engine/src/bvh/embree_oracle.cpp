#include "bvh/embree_oracle.h"

#include <algorithm>
#include <limits>

#include <embree3/rtcore.h>

#include "raybudget/error.h"

namespace raybudget::bvh {

struct EmbreeOracle::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<uint32_t> triObject;     // Embree primID -> object
  std::vector<uint32_t> triPrimitive;  // Embree primID -> triangle index in the mesh

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

EmbreeOracle::EmbreeOracle(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = rtcNewDevice(nullptr);
  if (!m.device) throw Error("Embree: rtcNewDevice failed");
  m.scene = rtcNewScene(m.device);
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
  size_t vertexCount = 0, triCount = 0;
  for (const Object& o : scene.objects) {
    vertexCount += scene.meshes[o.mesh].vertices.size();
    triCount += scene.meshes[o.mesh].indices.size() / 3;
  }
  RTCGeometry geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
  auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triCount));
  if (!vb || !ib) throw Error("Embree: geometry buffer allocation failed");
  size_t v = 0, t = 0;
  for (const Object& o : scene.objects) {
    const Mesh& mesh = scene.meshes[o.mesh];
    const uint32_t base = uint32_t(v);
    for (const Vertex& vx : mesh.vertices) {
      const glm::vec3 w = glm::vec3(o.transform * glm::vec4(vx.position, 1.0f));
      vb[v * 3] = w.x;
      vb[v * 3 + 1] = w.y;
      vb[v * 3 + 2] = w.z;
      ++v;
    }
    for (size_t i = 0; i < mesh.indices.size(); i += 3, ++t) {
      ib[t * 3] = base + mesh.indices[i];
      ib[t * 3 + 1] = base + mesh.indices[i + 1];
      ib[t * 3 + 2] = base + mesh.indices[i + 2];
      m.triObject.push_back(o.id);
      m.triPrimitive.push_back(uint32_t(i / 3));
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(m.scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(m.scene);
}

EmbreeOracle::~EmbreeOracle() = default;

namespace {

RTCRay toRtc(const OracleRay& r) {
  RTCRay ray{};
  ray.org_x = r.origin.x;
  ray.org_y = r.origin.y;
  ray.org_z = r.origin.z;
  ray.dir_x = r.dir.x;
  ray.dir_y = r.dir.y;
  ray.dir_z = r.dir.z;
  ray.tnear = r.tMin;
  ray.tfar = r.tMax;
  ray.mask = 0xFFFFFFFFu;
  return ray;
}

// Rays base..base+7 into a packet; lanes past `count` are invalid (copies of the last ray).
void fillPacket(const OracleRay* rays, size_t count, size_t base, RTCRay8& ray, int* valid) {
  for (int k = 0; k < 8; ++k) {
    const size_t i = base + size_t(k);
    valid[k] = i < count ? -1 : 0;
    const OracleRay& r = rays[std::min(i, count - 1)];
    ray.org_x[k] = r.origin.x;
    ray.org_y[k] = r.origin.y;
    ray.org_z[k] = r.origin.z;
    ray.dir_x[k] = r.dir.x;
    ray.dir_y[k] = r.dir.y;
    ray.dir_z[k] = r.dir.z;
    ray.tnear[k] = r.tMin;
    ray.tfar[k] = r.tMax;
    ray.mask[k] = 0xFFFFFFFFu;
  }
}

}  // namespace

OracleHit EmbreeOracle::intersect(const OracleRay& r) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray = toRtc(r);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  OracleHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.object = impl_->triObject[rh.hit.primID];
  h.primitive = impl_->triPrimitive[rh.hit.primID];
  h.barycentrics = {rh.hit.u, rh.hit.v};
  return h;
}

bool EmbreeOracle::occluded(const OracleRay& r) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray = toRtc(r);
  rtcOccluded1(impl_->scene, &ctx, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void EmbreeOracle::intersect8(const OracleRay* rays, size_t count, OracleHit* hits) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (size_t base = 0; base < count; base += 8) {
    alignas(32) int valid[8];
    alignas(32) RTCRayHit8 rh{};
    fillPacket(rays, count, base, rh.ray, valid);
    for (int k = 0; k < 8; ++k) rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect8(valid, impl_->scene, &ctx, &rh);
    for (int k = 0; k < 8 && base + size_t(k) < count; ++k) {
      OracleHit& h = hits[base + size_t(k)];
      h = OracleHit{};
      if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
      h.hit = true;
      h.t = rh.ray.tfar[k];
      h.object = impl_->triObject[rh.hit.primID[k]];
      h.primitive = impl_->triPrimitive[rh.hit.primID[k]];
      h.barycentrics = {rh.hit.u[k], rh.hit.v[k]};
    }
  }
}

void EmbreeOracle::occluded8(const OracleRay* rays, size_t count, bool* blocked) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (size_t base = 0; base < count; base += 8) {
    alignas(32) int valid[8];
    alignas(32) RTCRay8 ray{};
    fillPacket(rays, count, base, ray, valid);
    rtcOccluded8(valid, impl_->scene, &ctx, &ray);
    for (int k = 0; k < 8 && base + size_t(k) < count; ++k) blocked[base + size_t(k)] = ray.tfar[k] < 0.0f;
  }
}

}  // namespace raybudget::bvh
