// Which cases a command acts on, and the commands printed to act on exactly some of them.
#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>

#include "harness/escape.hpp"
#include "harness/invocation.hpp"
#include "harness/runner.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

void set_shard(Selection& s, const std::string& text) {
  std::string spec = text;
  if (spec.empty()) {
    const char* index = std::getenv("GTEST_SHARD_INDEX");
    const char* total = std::getenv("GTEST_TOTAL_SHARDS");
    if (!index || !total) return;
    spec = fmt::format("{}/{}", index, total);
  }
  const std::size_t slash = spec.find('/');
  try {
    std::size_t used_i = 0, used_n = 0;
    s.shard_index = std::stoi(spec.substr(0, slash), &used_i);
    s.shard_count = std::stoi(spec.substr(slash + 1), &used_n);
    if (slash == std::string::npos || used_i != slash || used_n != spec.size() - slash - 1) {
      throw std::invalid_argument("");
    }
  } catch (const std::exception&) {
    throw std::invalid_argument("shard '" + spec + "' is not i/n");
  }
  if (s.shard_count < 1 || s.shard_index < 0 || s.shard_index >= s.shard_count) {
    throw std::invalid_argument("shard '" + spec + "' needs 0 <= i < n");
  }
}

std::vector<const Case*> select(const Suite& suite, const Selection& s) {
  std::optional<std::regex> re;
  if (!s.filter.empty()) {
    try {
      re.emplace(s.filter, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      throw std::invalid_argument("--filter '" + s.filter + "': " + e.what());
    }
  }
  std::vector<const Case*> kept;
  for (const Case& c : suite.cases) {
    if (!re || std::regex_search(c.id, *re)) kept.push_back(&c);
  }
  std::vector<const Case*> out;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (static_cast<int>(i % s.shard_count) == s.shard_index) out.push_back(kept[i]);
  }
  return out;
}

std::string bless_prefix(const Suite& suite) {
  if (!suite.bless_prefix.empty()) return suite.bless_prefix;
  std::string out = program_command() + " bless " + shell_quote(suite.file.string());
  if (suite.goldens_given) out += " --goldens " + shell_quote(suite.goldens.string());
  return out;
}

std::string exact_filter(const std::vector<std::string>& ids) {
  std::string alternatives;
  for (const std::string& id : ids) {
    if (!alternatives.empty()) alternatives += '|';
    for (const char ch : id) {
      if (std::string_view("\\^$.|?*+()[]{}").find(ch) != std::string_view::npos) {
        alternatives += '\\';
      }
      alternatives += ch;
    }
  }
  return ids.size() == 1 ? "^" + alternatives + "$" : "^(" + alternatives + ")$";
}

std::string bless_command(std::string_view prefix, const std::vector<std::string>& ids) {
  return fmt::format("{} --filter {}", prefix, shell_quote(exact_filter(ids)));
}

std::string accept_report_command(std::string_view prefix,
                                  const std::filesystem::path& report_dir) {
  return fmt::format("{} --failed --report {}", prefix, shell_quote(report_dir.string()));
}

std::string report_page(const std::filesystem::path& report_dir) {
  return (std::filesystem::absolute(report_dir).lexically_normal() / "index.html").string();
}

std::string report_panel(const std::filesystem::path& report_dir, std::string_view case_id) {
  return report_page(report_dir) + "#case=" + std::string(case_id);
}

namespace {

std::string list_command(const Suite& suite) {
  return program_command() + " check " +
         (suite.check_args.empty() ? shell_quote(suite.file.string()) : suite.check_args) +
         " --list";
}

}  // namespace

std::vector<const Case*> select_some(const Suite& suite, const Selection& s) {
  std::vector<const Case*> cases = select(suite, s);
  if (!cases.empty()) return cases;
  std::string why =
      s.filter.empty() ? std::string("the suite") : "--filter " + shell_quote(s.filter);
  if (s.shard_count > 1) why += fmt::format(" with shard {}/{}", s.shard_index, s.shard_count);
  throw std::invalid_argument(fmt::format(
      "{}: {} selects none of its {} cases; nothing was run (ids: {})",
      printable(suite.file.string()), printable(why), suite.cases.size(), list_command(suite)));
}

}  // namespace aosuite::harness
