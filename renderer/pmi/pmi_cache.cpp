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

std::size_t pmi_maps_bytes(const PmiMaps& m) {
  const auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
  const PmiChannel& c = m.channel;
  return bytes(m.object.positions) + bytes(m.object.triangles) + bytes(m.object.mesh_vertex_base) +
         bytes(c.viewpoints) + bytes(c.view_probability) + bytes(c.polygon_probability) +
         bytes(c.pmi) + bytes(c.vmi) + bytes(c.view_pmi) + bytes(c.colour_pmi) +
         bytes(m.polygon_visibility) + bytes(m.vertex_visibility);
}

std::shared_ptr<const PmiMaps> PmiCache::get(const Scene& scene, const PmiSettings& settings) {
  const std::uint64_t key = pmi_content_hash(scene, settings);
  if (const auto hit = entries_.find(key); hit != entries_.end()) {
    hit->second.used = ++clock_;
    return hit->second.maps;
  }
  ++misses_;
  auto maps = std::make_shared<const PmiMaps>(compute_pmi_maps(scene, settings));
  const std::size_t bytes = pmi_maps_bytes(*maps);
  entries_[key] = {maps, bytes, ++clock_};
  bytes_ += bytes;
  while (bytes_ > budget_ && entries_.size() > 1) {
    const auto oldest =
        std::ranges::min_element(entries_, {}, [](const auto& e) { return e.second.used; });
    bytes_ -= oldest->second.bytes;
    entries_.erase(oldest);
  }
  return maps;
}

}  // namespace aosuite::renderer
