// PMI's maps are view-independent: computed once per scene content and settings, then reused
// by every view and frame the Renderer draws.
#pragma once

#include <cstdint>
#include <map>
#include <memory>

#include "renderer/pmi/pmi_channel.hpp"

namespace aosuite::renderer {

class PmiCache {
 public:
  // Holds maps up to `budget_bytes` in all (the least recently used dropped first, the newest
  // always kept): a tune or sweep that visits every scene in turn computes each once, where a
  // cap on the count of scenes would recompute them all on every pass.
  explicit PmiCache(std::size_t budget_bytes = std::size_t{256} << 20) : budget_(budget_bytes) {}
  // Needs a current GL context on a miss.
  std::shared_ptr<const PmiMaps> get(const Scene& scene, const PmiSettings& settings);
  std::size_t misses() const { return misses_; }

 private:
  struct Entry {
    std::shared_ptr<const PmiMaps> maps;
    std::size_t bytes = 0;
    std::uint64_t used = 0;  // clock_ at the last get
  };
  std::size_t budget_;
  std::map<std::uint64_t, Entry> entries_;
  std::size_t bytes_ = 0;
  std::uint64_t clock_ = 0;
  std::size_t misses_ = 0;
};

// What a PmiMaps holds in memory (its vectors' contents).
std::size_t pmi_maps_bytes(const PmiMaps& maps);

// The content the maps depend on: geometry, ground flags and settings (not colours or views).
std::uint64_t pmi_content_hash(const Scene& scene, const PmiSettings& settings);

}  // namespace aosuite::renderer
