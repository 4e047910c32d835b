#include "reference/embree_scene.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace aosuite::reference {
namespace {

void check_device(RTCDevice device, const char* what) {
  if (const RTCError e = rtcGetDeviceError(device); e != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                             std::to_string(static_cast<int>(e)) + ")");
  }
}

void add_mesh(RTCDevice device, RTCScene scene, const renderer::Mesh& m) {
  if (m.triangles.empty()) return;
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree pads its own buffers (it reads 16 bytes past a float3), so the data is copied.
  void* v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    sizeof(glm::vec3), m.positions.size());
  void* t = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    sizeof(glm::uvec3), m.triangles.size());
  check_device(device, "geometry buffers");
  std::memcpy(v, m.positions.data(), m.positions.size() * sizeof(glm::vec3));
  std::memcpy(t, m.triangles.data(), m.triangles.size() * sizeof(glm::uvec3));
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  check_device(device, "geometry commit");
}

}  // namespace

EmbreeScene::EmbreeScene(const renderer::Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  // Robust traversal: AO rays start a hair above surfaces and graze creases.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);  // hundreds of rays per pixel
  try {
    for (const renderer::Mesh& m : scene.meshes) add_mesh(device_, scene_, m);
    rtcCommitScene(scene_);
    check_device(device_, "scene build");
  } catch (...) {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw;
  }
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

}  // namespace aosuite::reference
