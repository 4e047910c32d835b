// The report folder's cache.json: the last result of every case run there (any selection), by
// id: what tells an unchanged case. One file, read once and written once per run (thousands of
// small files cost more than their bytes). A damaged cache only costs re-running.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "harness/results.hpp"

namespace aosuite::harness {

using Cache = std::map<std::string, CaseResult>;

Cache load_cache(const std::filesystem::path& report_dir);
// Records `ran` over what was cached; what only describes one run (its time, whether it was
// reused) is left out.
void save_cache(const std::filesystem::path& report_dir, Cache cache,
                const std::vector<CaseResult>& ran);

// The content hash image_hashes records.
std::string bytes_hash(const std::vector<unsigned char>& bytes);

}  // namespace aosuite::harness
