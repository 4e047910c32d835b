#include "renderer/pmi/pmi_cache.hpp"

#include <algorithm>

#include "common/content_hash.hpp"

namespace aosuite::renderer {

std::uint64_t pmi_content_hash(const Scene& scene, const PmiSettings& s) {
  ContentHash h;
  for (const Mesh& m : scene.meshes) {
    h.add(std::span(m.positions)).add(std::span(m.triangles)).add(m.ground);
  }
  h.add(s.viewpoints)
      .add(s.width)
      .add(s.height)
      .add(s.importance_best)
      .add(s.per_view)
      .add(s.colour);
  return h.digest();
}

std::shared_ptr<const PmiMaps> PmiCache::get(const Scene& scene, const PmiSettings& settings) {
  const std::uint64_t key = pmi_content_hash(scene, settings);
  age_[key] = ++clock_;
  auto& entry = entries_[key];
  if (!entry) {
    ++misses_;
    try {
      entry = std::make_shared<const PmiMaps>(compute_pmi_maps(scene, settings));
    } catch (...) {
      entries_.erase(key), age_.erase(key);
      throw;
    }
    if (entries_.size() > kEntries) {
      const auto oldest = std::min_element(age_.begin(), age_.end(), [](auto& a, auto& b) {
                            return a.second < b.second;
                          })->first;
      entries_.erase(oldest), age_.erase(oldest);
    }
  }
  return entry;
}

}  // namespace aosuite::renderer
