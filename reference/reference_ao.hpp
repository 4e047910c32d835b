// Ray-traced ground truth for screen-space AO: A = (1/pi) * integral of V(w) cos(theta) dw over
// the hemisphere of the G-buffer normal, estimated with cosine-weighted Hammersley directions
// (a per-pixel Cranley-Patterson rotation decorrelates neighbours), traced with Embree in
// packets of 16 from the rasterised surface points, so reference and technique see the same
// pixels. Per-pixel spread <= sqrt(A(1-A)/N) <= 0.5/sqrt(N) (the i.i.d. bound; the
// stratified directions do better).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <string_view>

#include "reference/embree_scene.hpp"
#include "renderer/frame.hpp"

namespace aosuite::reference {

enum class Variant {
  kAo,          // V = 1 when no hit within the radius (near-field AO)
  kObscurance,  // rho(L) = 1 - (1 - (L/r)^2)^3 for a first hit at L < r, else 1 (SAO's falloff)
  kUnbounded,   // V = 1 when the ray never hits (the radius is ignored)
};
Variant parse_variant(std::string_view name);  // ao|obscurance|unbounded
std::string_view variant_name(Variant v);

struct ReferenceSettings {
  int rays = 256;    // per pixel
  float radius = 1;  // scene units: the technique's radius
  Variant variant = Variant::kAo;
};
// Throws std::invalid_argument for rays outside 1..65536 or a radius that is not a positive
// finite number.
void validate(const ReferenceSettings& s);

// A at one world-space surface point; `key` picks the point's rotation of the directions.
float occlusion_at(const EmbreeScene& scene, glm::vec3 position, glm::vec3 normal,
                   std::uint64_t key, const ReferenceSettings& s);

// A for every pixel of a G-buffer made with `camera`: depth (CV_32F, 0 = background) and
// view-space normals (CV_32FC3, Images::normal). CV_32F like Images::ao, 1 on background.
// Rows are split over `threads` threads (0: all cores).
cv::Mat reference_ao(const EmbreeScene& scene, const renderer::Camera& camera, const cv::Mat& depth,
                     const cv::Mat& normal, const ReferenceSettings& s, int threads = 0);

}  // namespace aosuite::reference
