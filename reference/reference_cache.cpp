#include "reference/reference_cache.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <cstring>

#include "compare/image_io.hpp"
#include "renderer/content_hash.hpp"

namespace aosuite::reference {
namespace {

namespace fs = std::filesystem;

// Positions and triangles only: colours do not change visibility, and normals enter through
// the G-buffer's normal image.
std::uint64_t geometry_hash(const renderer::Scene& scene) {
  ContentHash h;
  for (const renderer::Mesh& m : scene.meshes)
    h.add(std::span(m.positions)).add(std::span(m.triangles));
  return h.digest();
}

// File layout: "AOREF1\0\0", int32 width, int32 height, then width*height little-endian floats.
constexpr char kMagic[8] = {'A', 'O', 'R', 'E', 'F', '1', 0, 0};

cv::Mat load(const fs::path& path, int w, int h) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return {};
  const std::vector<unsigned char> bytes = read_file(path);
  const std::size_t expected = sizeof kMagic + 8 + std::size_t(w) * std::size_t(h) * 4;
  int size[2] = {0, 0};
  if (bytes.size() != expected || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return {};
  std::memcpy(size, bytes.data() + sizeof kMagic, sizeof size);
  if (size[0] != w || size[1] != h) return {};
  cv::Mat m(h, w, CV_32F);
  std::memcpy(m.data, bytes.data() + sizeof kMagic + 8, m.total() * 4);
  // A damaged file must not smuggle NaN into the metrics: recompute instead.
  if (!cv::checkRange(m, true, nullptr, 0.0, 1.0 + 1e-6)) return {};
  return m;
}

void store(const fs::path& path, const cv::Mat& ao) {
  std::vector<unsigned char> bytes(sizeof kMagic + 8 + ao.total() * 4);
  const int size[2] = {ao.cols, ao.rows};
  std::memcpy(bytes.data(), kMagic, sizeof kMagic);
  std::memcpy(bytes.data() + sizeof kMagic, size, sizeof size);
  std::memcpy(bytes.data() + sizeof kMagic + 8, ao.data, ao.total() * 4);
  fs::create_directories(path.parent_path());
  write_file_atomic(path, bytes);
}

}  // namespace

fs::path default_cache_dir() {
  if (const char* env = std::getenv("AOSUITE_REFERENCE_CACHE"); env && *env) return env;
  return fs::path(AOSUITE_CACHE_DIR) / "reference";
}

ReferenceCache::ReferenceCache(const renderer::Scene& scene, fs::path dir)
    : scene_(scene), dir_(std::move(dir)), scene_hash_(geometry_hash(scene)) {}
ReferenceCache::~ReferenceCache() = default;

std::string ReferenceCache::key(const renderer::Camera& camera, const cv::Mat& depth,
                                const cv::Mat& normal, const ReferenceSettings& s) const {
  ContentHash h;
  h.add(kReferenceVersion).add(scene_hash_);
  h.add(camera.width).add(camera.height).add(camera.view).add(camera.ndc_to_view);
  h.add(depth).add(normal);
  const float radius = s.variant == Variant::kUnbounded ? 0.0f : s.radius;
  h.add(s.rays).add(radius).add(static_cast<int>(s.variant));
  return h.hex();
}

cv::Mat ReferenceCache::get(const renderer::Camera& camera, const cv::Mat& depth,
                            const cv::Mat& normal, const ReferenceSettings& s) {
  validate(s);
  const fs::path file =
      dir_.empty() ? fs::path() : dir_ / (key(camera, depth, normal, s) + ".aoref");
  if (!file.empty()) {
    if (cv::Mat cached = load(file, depth.cols, depth.rows); !cached.empty()) {
      last_cached_ = true, last_seconds_ = 0;
      return cached;
    }
  }
  if (!embree_) embree_ = std::make_unique<EmbreeScene>(scene_);
  const auto start = std::chrono::steady_clock::now();
  cv::Mat ao = reference_ao(*embree_, camera, depth, normal, s);
  last_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  last_cached_ = false;
  if (!file.empty()) store(file, ao);
  return ao;
}

}  // namespace aosuite::reference
