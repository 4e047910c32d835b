// Ray-traced references cost seconds to minutes; they are kept on disk, keyed by an xxh3 hash
// of everything they depend on, and the Embree scene is only built on a miss.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "reference/embree_scene.hpp"
#include "reference/reference_ao.hpp"

namespace aosuite::reference {

// Bump when the estimator changes what it computes (sampling, offsets, falloff).
inline constexpr int kReferenceVersion = 1;

// $AOSUITE_REFERENCE_CACHE when set, else the repository's .cache/reference/ (ignored by git).
std::filesystem::path default_cache_dir();

// The most the cache directory may hold: $AOSUITE_REFERENCE_CACHE_MB megabytes when set
// (0: no limit), else 2048 MB, enough for the full thesis grid at 720p and 1080p.
std::uint64_t default_cache_limit();

// Deletes the least recently used references (oldest modification time: a hit touches its
// file) until `dir` holds at most `limit_bytes` of them; `keep` is never deleted. Returns
// the number of files deleted. Files that vanish meanwhile (another process pruning) and
// files that are not references are left alone.
int prune_cache(const std::filesystem::path& dir, std::uint64_t limit_bytes,
                const std::filesystem::path& keep = {});

class ReferenceCache {
 public:
  // `scene` must outlive the cache. An empty `dir` disables the disk cache; after each new
  // reference the directory is pruned to `limit_bytes` (0: unbounded).
  ReferenceCache(const renderer::Scene& scene, std::filesystem::path dir,
                 std::uint64_t limit_bytes = default_cache_limit());
  ~ReferenceCache();

  // The reference for a G-buffer (depth, view-space normal) made with `camera`: from disk
  // when a file with the same key exists, else traced and written atomically.
  cv::Mat get(const renderer::Camera& camera, const cv::Mat& depth, const cv::Mat& normal,
              const ReferenceSettings& settings);
  bool last_was_cached() const { return last_cached_; }
  double last_seconds() const { return last_seconds_; }  // tracing time of the last miss

  // Scene geometry, camera, G-buffer, settings and kReferenceVersion, as 16 hex digits.
  std::string key(const renderer::Camera& camera, const cv::Mat& depth, const cv::Mat& normal,
                  const ReferenceSettings& settings) const;

 private:
  const renderer::Scene& scene_;
  std::filesystem::path dir_;
  std::uint64_t limit_bytes_;
  std::uint64_t scene_hash_;
  std::unique_ptr<EmbreeScene> embree_;
  bool last_cached_ = false;
  double last_seconds_ = 0;
};

}  // namespace aosuite::reference
