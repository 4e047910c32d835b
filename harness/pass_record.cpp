#include "harness/pass_record.hpp"

#include <nlohmann/json.hpp>

#include "common/file_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

fs::path pass_record(const fs::path& golden) {
  return golden.parent_path() / (golden.stem().string() + ".passes.json");
}

std::vector<unsigned char> pass_record_bytes(const PassHashes& passes) {
  const std::string text = nlohmann::json(passes).dump() + "\n";
  return {text.begin(), text.end()};
}

PassHashes read_pass_record(const fs::path& golden) {
  try {
    const std::vector<unsigned char> bytes = read_regular_file(pass_record(golden));
    return nlohmann::json::parse(bytes).get<PassHashes>();
  } catch (const std::exception&) {
    return {};  // an explanation is a courtesy: without one the verdict still stands
  }
}

std::string first_differing_pass(const PassHashes& golden, const PassHashes& now) {
  if (golden.empty() || golden.size() != now.size()) return "";
  std::string same;
  for (std::size_t i = 0; i < now.size(); ++i) {
    if (golden[i].first != now[i].first) return "";
    if (golden[i].second != now[i].second)
      return now[i].first + " differs" + (same.empty() ? "" : " (" + same + " identical)");
    same += (same.empty() ? "" : ", ") + now[i].first;
  }
  return "every pass identical";
}

}  // namespace aosuite::harness
