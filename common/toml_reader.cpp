#include "common/toml_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "common/file_io.hpp"
#include "common/printable.hpp"

namespace aosuite {

void TomlReader::fail(const toml::source_region& at, std::string_view why) const {
  // `why` may quote the file (a key, a string, toml++'s description of bad bytes): escaped.
  throw FileError(
      printable(fmt::format("{}:{}:{}: {}", file_.string(), at.begin.line, at.begin.column, why)));
}

void TomlReader::only_keys(const toml::table& t,
                           std::initializer_list<std::string_view> known) const {
  only_keys(t, std::span<const std::string_view>(known.begin(), known.size()));
}

void TomlReader::only_keys(const toml::table& t, std::span<const std::string_view> known) const {
  for (const auto& [key, value] : t) {
    if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
    std::string list;
    for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    fail(key.source(), fmt::format("unknown key '{}' (expected one of: {})", key.str(), list));
  }
}

const toml::node& TomlReader::required(const toml::table& t, std::string_view key) const {
  if (const toml::node* n = t.get(key)) return *n;
  fail(t.source(), fmt::format("missing '{}'", key));
}

std::string TomlReader::string(const toml::node& n, std::string_view what) const {
  if (auto v = n.value_exact<std::string>()) return *v;
  fail(n.source(), fmt::format("{} must be a string", what));
}

std::string TomlReader::param(const toml::node& n) const {
  if (const toml::array* a = n.as_array()) {
    std::string out;
    for (const toml::node& e : *a) {
      if (!out.empty()) out += ',';
      out += param(e);
    }
    return out;
  }
  if (auto s = n.value_exact<std::string>()) return *s;
  if (auto i = n.value_exact<std::int64_t>()) return std::to_string(*i);
  if (auto d = n.value_exact<double>()) return fmt::format("{}", *d);
  fail(n.source(), "a parameter must be a number, a string or an array of numbers");
}

bool TomlReader::boolean(const toml::node& n, std::string_view what) const {
  if (auto v = n.value_exact<bool>()) return *v;
  fail(n.source(), fmt::format("{} must be true or false", what));
}

int TomlReader::integer(const toml::node& n, std::string_view what, std::int64_t lo,
                        std::int64_t hi) const {
  const auto v = n.value_exact<std::int64_t>();
  if (!v) fail(n.source(), fmt::format("{} must be an integer", what));
  if (*v < lo || *v > hi)
    fail(n.source(), fmt::format("{} must be {}..{}, not {}", what, lo, hi, *v));
  return static_cast<int>(*v);
}

double TomlReader::number(const toml::node& n, std::string_view what) const {
  std::optional<double> v = n.value_exact<double>();
  if (const auto i = n.value_exact<std::int64_t>()) v = static_cast<double>(*i);
  if (!v) fail(n.source(), fmt::format("{} must be a number", what));
  if (!std::isfinite(*v) || !std::isfinite(static_cast<float>(*v)))
    fail(n.source(), fmt::format("{} must be finite", what));
  return *v;
}

double TomlReader::positive(const toml::node& n, std::string_view what) const {
  const double v = number(n, what);
  if (!(v > 0)) fail(n.source(), fmt::format("{} must be positive", what));
  // Sizes are used as floats: one that rounds to 0 or to a denormal (1e-300) is no size.
  if (!(static_cast<float>(v) >= std::numeric_limits<float>::min())) {
    fail(n.source(), fmt::format("{} is too small (below 1.2e-38, the least normal float)", what));
  }
  return v;
}

glm::vec3 TomlReader::vec3(const toml::node& n, std::string_view what) const {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 3) fail(n.source(), fmt::format("{} must be an array of 3 numbers", what));
  auto f = [&](std::size_t i) { return static_cast<float>(number((*a)[i], what)); };
  return {f(0), f(1), f(2)};
}

std::vector<std::string> TomlReader::strings(const toml::node& n, std::string_view what,
                                             bool allow_empty) const {
  const toml::array* a = n.as_array();
  if (!a) fail(n.source(), fmt::format("{} must be an array of strings", what));
  std::vector<std::string> out;
  for (const toml::node& e : *a) out.push_back(string(e, what));
  if (out.empty() && !allow_empty) fail(n.source(), fmt::format("{} must not be empty", what));
  return out;
}

const toml::table& TomlReader::table(const toml::node& n, std::string_view what) const {
  if (const toml::table* t = n.as_table()) return *t;
  fail(n.source(), fmt::format("{} must be a table", what));
}

std::vector<const toml::table*> TomlReader::tables(const toml::node& n,
                                                   std::string_view what) const {
  const toml::array* a = n.as_array();
  if (!a) fail(n.source(), fmt::format("{} must be an array of tables ([[{}]])", what, what));
  std::vector<const toml::table*> out;
  for (const toml::node& e : *a) out.push_back(&table(e, what));
  if (out.empty()) fail(n.source(), fmt::format("{} must not be empty", what));
  return out;
}

std::string TomlReader::name(const toml::node& n, std::string_view what) const {
  const std::string s = string(n, what);
  const bool safe = !s.empty() && s.front() != '.' && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!safe) fail(n.source(), fmt::format("{} '{}' must be letters, digits, _ - .", what, s));
  return s;
}

}  // namespace aosuite
