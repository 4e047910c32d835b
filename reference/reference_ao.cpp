#include "reference/reference_ao.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace aosuite::reference {
namespace {

constexpr int kPacket = 16;

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

float unit_float(std::uint32_t bits) { return static_cast<float>(bits >> 8) * 0x1p-24f; }

float radical_inverse(std::uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  return unit_float(i);
}

// Shirley-Chiu concentric map of the unit square to the unit disk: it keeps the Hammersley
// points' stratification, and lifting the disk to the hemisphere (Malley) makes them
// cosine-distributed.
glm::vec3 cosine_direction(float u, float v) {
  const float a = 2 * u - 1, b = 2 * v - 1;
  if (a == 0 && b == 0) return {0, 0, 1};
  constexpr float kQuarterPi = 0.785398163f;
  float r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a, phi = kQuarterPi * (b / a);
  } else {
    r = b, phi = 2 * kQuarterPi - kQuarterPi * (a / b);
  }
  const float x = r * std::cos(phi), y = r * std::sin(phi);
  return {x, y, std::sqrt(std::max(0.0f, 1 - x * x - y * y))};
}

// Duff et al. 2017: an orthonormal basis around unit n without a branch on a near-pole.
void basis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1 / (sign + n.z), c = n.x * n.y * a;
  t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

float obscurance_weight(float hit, float radius) {
  const float q = 1 - (hit / radius) * (hit / radius);
  return 1 - q * q * q;
}

}  // namespace

Variant parse_variant(std::string_view name) {
  if (name == "ao") return Variant::kAo;
  if (name == "obscurance") return Variant::kObscurance;
  if (name == "unbounded") return Variant::kUnbounded;
  throw std::invalid_argument("unknown reference variant '" + std::string(name) +
                              "' (ao, obscurance, unbounded)");
}

std::string_view variant_name(Variant v) {
  switch (v) {
    case Variant::kAo:
      return "ao";
    case Variant::kObscurance:
      return "obscurance";
    case Variant::kUnbounded:
      return "unbounded";
  }
  return "?";
}

void validate(const ReferenceSettings& s) {
  if (s.rays < 1 || s.rays > 65536) throw std::invalid_argument("rays must be 1..65536");
  if (!(s.radius > 0) || !std::isfinite(s.radius))
    throw std::invalid_argument("reference radius must be a positive number");
}

float occlusion_at(const EmbreeScene& scene, glm::vec3 position, glm::vec3 normal,
                   std::uint64_t key, const ReferenceSettings& s) {
  glm::vec3 t, b;
  basis(normal, t, b);
  const std::uint64_t h = splitmix64(key);
  const float rot_u = unit_float(static_cast<std::uint32_t>(h)),
              rot_v = unit_float(static_cast<std::uint32_t>(h >> 32));
  const float tfar =
      s.variant == Variant::kUnbounded ? std::numeric_limits<float>::infinity() : s.radius;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one origin, one hemisphere
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacket];
  double sum = 0;
  for (int first = 0; first < s.rays; first += kPacket) {
    RTCRay16& r = packet.ray;
    for (int k = 0; k < kPacket; ++k) {
      const int i = first + k;
      valid[k] = i < s.rays ? -1 : 0;
      const float u =
          std::fmod((static_cast<float>(i) + 0.5f) / static_cast<float>(s.rays) + rot_u, 1.0f);
      const float v = std::fmod(radical_inverse(static_cast<std::uint32_t>(i)) + rot_v, 1.0f);
      const glm::vec3 d0 = cosine_direction(u, v);
      const glm::vec3 d = d0.x * t + d0.y * b + d0.z * normal;
      r.org_x[k] = position.x, r.org_y[k] = position.y, r.org_z[k] = position.z;
      r.dir_x[k] = d.x, r.dir_y[k] = d.y, r.dir_z[k] = d.z;
      r.tnear[k] = 0, r.tfar[k] = tfar, r.time[k] = 0;
      r.mask[k] = ~0u, r.id[k] = static_cast<unsigned>(k), r.flags[k] = 0;
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    if (s.variant == Variant::kObscurance) {
      rtcIntersect16(valid, scene.get(), &context, &packet);
      for (int k = 0; k < kPacket; ++k) {
        if (!valid[k]) continue;
        const bool hit = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        sum += hit ? obscurance_weight(r.tfar[k], s.radius) : 1.0;
      }
    } else {
      rtcOccluded16(valid, scene.get(), &context, &r);
      for (int k = 0; k < kPacket; ++k) {
        if (valid[k] && r.tfar[k] >= 0) sum += 1;  // an occluded ray's tfar becomes -inf
      }
    }
  }
  return static_cast<float>(sum / s.rays);
}

cv::Mat reference_ao(const EmbreeScene& scene, const renderer::Camera& camera, const cv::Mat& depth,
                     const cv::Mat& normal, const ReferenceSettings& s, int threads) {
  validate(s);
  if (depth.type() != CV_32F || normal.type() != CV_32FC3 || depth.size() != normal.size() ||
      depth.cols != camera.width || depth.rows != camera.height) {
    throw std::invalid_argument(
        "reference_ao: depth (CV_32F) and normal (CV_32FC3) must match the camera's size");
  }
  const glm::mat4 to_world = glm::inverse(camera.view);
  const glm::mat3 rotate_to_world(to_world);
  const glm::vec3 eye(to_world[3]);
  cv::Mat ao(depth.size(), CV_32F, cv::Scalar(1));
  std::atomic<int> next_row{0};
  auto work = [&] {
    for (int y; (y = next_row++) < depth.rows;) {
      for (int x = 0; x < depth.cols; ++x) {
        const float z = depth.at<float>(y, x);
        if (!(z > 0)) continue;
        const cv::Vec3f nv = normal.at<cv::Vec3f>(y, x);
        const glm::vec3 p_view = renderer::view_position(camera, x, y, z);
        glm::vec3 n = rotate_to_world * glm::vec3(nv[0], nv[1], nv[2]);
        // The G-buffer always writes a unit normal; should one be missing, face the camera.
        n = glm::length(n) > 0.5f ? glm::normalize(n) : glm::normalize(rotate_to_world * -p_view);
        const glm::vec3 p = glm::vec3(to_world * glm::vec4(p_view, 1));
        // Scale-aware offset: raster depth is accurate to ~1e-6 of the view distance, world
        // coordinates to ~1e-7 of their magnitude; 100x margins on both.
        const float offset = 1e-4f * z + 1e-5f * glm::length(p - eye) + 1e-5f * glm::length(p);
        const std::uint64_t key =
            static_cast<std::uint64_t>(y) * 65536u + static_cast<std::uint64_t>(x);
        ao.at<float>(y, x) = occlusion_at(scene, p + offset * n, n, key, s);
      }
    }
  };
  const int n_threads =
      threads > 0 ? threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int i = 1; i < n_threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return ao;
}

}  // namespace aosuite::reference
