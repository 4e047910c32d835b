#include "ao/sweep_merge.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <optional>

#include "image/image_io.hpp"

namespace aosuite::ao {

namespace fs = std::filesystem;

SweepResult merge_sweeps(const std::vector<std::string>& shard_dirs) {
  std::optional<SweepMeta> meta;
  std::map<std::size_t, Row> by_index;
  for (const std::string& d : shard_dirs) {
    const fs::path file = fs::path(d) / "sweep.json";
    SweepMeta m;
    std::vector<Row> rows;
    try {
      const std::vector<unsigned char> bytes = read_file(file);
      const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end());
      // A sweep.json from before the compute pipeline (issue 44) timed the fragment one.
      m = {j.at("grid"), j.at("gl"),   j.at("gl_device"), j.value("pipeline", "fragment"),
           j.at("rays"), j.at("runs"), j.at("unbounded"), j.at("configurations")};
      for (const nlohmann::json& r : j.at("rows")) rows.push_back(row_from_json(r));
    } catch (const FileError&) {
      throw;
    } catch (const std::exception& e) {
      throw FileError(file.string() + ": not a sweep.json: " + e.what());
    }
    if (!meta) meta = m;
    if (meta_json(m) != meta_json(*meta)) {
      throw FileError(file.string() + ": another grid, its settings, GL device or pipeline than " +
                      (fs::path(shard_dirs.front()) / "sweep.json").string());
    }
    for (Row& r : rows) {
      const std::size_t i = r.index;
      if (i >= m.configurations || !by_index.emplace(i, std::move(r)).second) {
        throw FileError(
            fmt::format("{}: configuration {} is out of range or in two shards", file.string(), i));
      }
    }
  }
  if (!meta || by_index.size() != meta->configurations) {
    throw std::invalid_argument(fmt::format("the shards hold {} of the grid's {} configurations",
                                            by_index.size(), meta ? meta->configurations : 0));
  }
  SweepResult merged{*meta, {}};
  for (auto& [i, r] : by_index) merged.rows.push_back(std::move(r));
  return merged;
}

}  // namespace aosuite::ao
