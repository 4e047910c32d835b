#include "renderer/pmi_cache.hpp"

#include <xxhash.h>

#include <algorithm>

namespace aosuite::renderer {

std::uint64_t pmi_content_hash(const Scene& scene, const PmiSettings& s) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  auto add = [&](const void* data, std::size_t bytes) { XXH3_64bits_update(state, data, bytes); };
  for (const Mesh& m : scene.meshes) {
    const std::size_t sizes[2] = {m.positions.size(), m.triangles.size()};
    add(sizes, sizeof sizes);
    add(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    add(m.triangles.data(), m.triangles.size() * sizeof(glm::uvec3));
    add(&m.ground, sizeof m.ground);
  }
  const int fields[6] = {s.viewpoints, s.width, s.height, s.importance_best, s.per_view, s.colour};
  add(fields, sizeof fields);
  const std::uint64_t hash = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return hash;
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
