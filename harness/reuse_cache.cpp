#include "harness/reuse_cache.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <span>

#include "common/content_hash.hpp"
#include "common/file_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

Cache load_cache(const fs::path& report_dir) {
  Cache cache;
  std::ifstream in(report_dir / "cache.json");
  if (!in) return cache;
  try {
    for (const nlohmann::json& j : nlohmann::json::parse(in)) {
      CaseResult c = case_from_json(j);
      cache[c.id] = std::move(c);
    }
  } catch (const std::exception&) {
    cache.clear();
  }
  return cache;
}

void save_cache(const fs::path& report_dir, Cache cache, const std::vector<CaseResult>& ran) {
  for (const CaseResult& r : ran) {
    CaseResult& saved = cache[r.id] = r;
    saved.seconds = 0, saved.reused = false, saved.not_reused.clear();
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto& [id, c] : cache) all.push_back(to_json(c));
  const std::string text = all.dump() + "\n";
  write_report_file(report_dir / "cache.json",
                    {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

std::string bytes_hash(const std::vector<unsigned char>& bytes) {
  return ContentHash().add(std::span<const unsigned char>(bytes)).hex();
}

}  // namespace aosuite::harness
