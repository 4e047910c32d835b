// A renderer::Scene as an Embree 3 scene in world space, for the ray-traced AO reference.
#pragma once

#include <embree3/rtcore.h>

#include "renderer/scene/scene.hpp"

namespace aosuite::reference {

class EmbreeScene {
 public:
  // Every mesh becomes one triangle geometry (two-sided: Embree reports hits on both faces).
  // Throws std::runtime_error if Embree cannot make a device or rejects the geometry.
  explicit EmbreeScene(const renderer::Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  RTCScene get() const { return scene_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace aosuite::reference
