#include "reference/reference_cache.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "common/cache_dir.hpp"
#include "common/content_hash.hpp"
#include "image/image_io.hpp"

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

// A matrix's shape, type and pixels (common/content_hash.hpp holds no OpenCV: the harness
// hashes without it).
void add_mat(ContentHash& h, const cv::Mat& m) {
  h.add(m.rows).add(m.cols).add(m.type());
  const cv::Mat c = m.isContinuous() ? m : m.clone();
  h.add(std::span<const unsigned char>(c.data, c.total() * c.elemSize()));
}

}  // namespace

fs::path default_cache_dir() {
  if (const char* env = std::getenv("AOSUITE_REFERENCE_CACHE"); env && *env) return env;
  return cache_dir(AOSUITE_CACHE_DIR) / "reference";
}

std::uint64_t default_cache_limit() {
  constexpr std::uint64_t kMb = 1 << 20;
  const char* env = std::getenv("AOSUITE_REFERENCE_CACHE_MB");
  if (!env || !*env) return 2048 * kMb;
  char* end = nullptr;
  const unsigned long long mb = std::strtoull(env, &end, 10);
  if (*end != '\0' || env[0] == '-') {
    throw std::invalid_argument(
        fmt::format("AOSUITE_REFERENCE_CACHE_MB='{}': expected a whole number of megabytes", env));
  }
  return mb * kMb;
}

int prune_cache(const fs::path& dir, std::uint64_t limit_bytes, const fs::path& keep) {
  struct Entry {
    fs::file_time_type used;
    std::uint64_t bytes;
    fs::path path;
  };
  std::vector<Entry> entries;
  std::uint64_t total = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() != ".aoref" || !e.is_regular_file(ec)) continue;
    const std::uint64_t bytes = e.file_size(ec);
    const fs::file_time_type used = e.last_write_time(ec);
    if (ec) continue;  // gone since listed
    entries.push_back({used, bytes, e.path()});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used < b.used; });
  int deleted = 0;
  for (const Entry& e : entries) {
    if (total <= limit_bytes) break;
    if (e.path == keep) continue;
    if (fs::remove(e.path, ec)) ++deleted;
    total -= e.bytes;  // removed here or by someone else: either way no longer held
  }
  return deleted;
}

ReferenceCache::ReferenceCache(const renderer::Scene& scene, fs::path dir,
                               std::uint64_t limit_bytes)
    : scene_(scene),
      dir_(std::move(dir)),
      limit_bytes_(limit_bytes),
      scene_hash_(geometry_hash(scene)) {}
ReferenceCache::~ReferenceCache() = default;

std::string ReferenceCache::key(const renderer::Camera& camera, const cv::Mat& depth,
                                const cv::Mat& normal, const ReferenceSettings& s) const {
  ContentHash h;
  h.add(kReferenceVersion).add(scene_hash_);
  h.add(camera.width).add(camera.height).add(camera.view).add(camera.ndc_to_view);
  add_mat(h, depth);
  add_mat(h, normal);
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
      std::error_code ec;  // recently used: pruned last (best effort on read-only caches)
      fs::last_write_time(file, fs::file_time_type::clock::now(), ec);
      return cached;
    }
  }
  if (!embree_) embree_ = std::make_unique<EmbreeScene>(scene_);
  const auto start = std::chrono::steady_clock::now();
  cv::Mat ao = reference_ao(*embree_, camera, depth, normal, s);
  last_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  last_cached_ = false;
  if (!file.empty()) {
    store(file, ao);
    if (limit_bytes_ > 0) prune_cache(dir_, limit_bytes_, file);
  }
  return ao;
}

}  // namespace aosuite::reference
