// PMI's maps are view-independent: computed once per scene content and settings, then reused
// by every view and frame the Renderer draws.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>

#include "renderer/pmi/pmi_channel.hpp"

namespace aosuite::renderer {

class PmiCache {
 public:
  // Needs a current GL context on a miss. Holds at most kEntries scenes (oldest dropped).
  std::shared_ptr<const PmiMaps> get(const Scene& scene, const PmiSettings& settings);
  std::size_t misses() const { return misses_; }

 private:
  static constexpr std::size_t kEntries = 4;
  std::map<std::uint64_t, std::shared_ptr<const PmiMaps>> entries_;
  std::map<std::uint64_t, std::uint64_t> age_;
  std::uint64_t clock_ = 0;
  std::size_t misses_ = 0;
};

// The content the maps depend on: geometry, ground flags and settings (not colours or views).
std::uint64_t pmi_content_hash(const Scene& scene, const PmiSettings& settings);

}  // namespace aosuite::renderer
