// Typed access to a parsed TOML file (scene files, suites) where every error names the file,
// line and column: "<file>:<line>:<column>: <reason>", thrown as aosuite::FileError.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aosuite {

class TomlReader {
 public:
  explicit TomlReader(std::filesystem::path file) : file_(std::move(file)) {}
  const std::filesystem::path& file() const { return file_; }

  [[noreturn]] void fail(const toml::source_region& at, std::string_view why) const;

  // Refuses any key of `t` not in `known`, listing the known ones.
  void only_keys(const toml::table& t, std::initializer_list<std::string_view> known) const;
  void only_keys(const toml::table& t, std::span<const std::string_view> known) const;
  const toml::node& required(const toml::table& t, std::string_view key) const;

  std::string string(const toml::node& n, std::string_view what) const;
  bool boolean(const toml::node& n, std::string_view what) const;
  int integer(const toml::node& n, std::string_view what, std::int64_t lo, std::int64_t hi) const;
  // A finite number (integer or float); TOML's nan and inf are refused.
  double number(const toml::node& n, std::string_view what) const;
  // A number() that is positive as a float too (at least the least normal float, 1.2e-38).
  double positive(const toml::node& n, std::string_view what) const;
  glm::vec3 vec3(const toml::node& n, std::string_view what) const;
  // An array of strings, non-empty unless `allow_empty` (a list that may say "none").
  std::vector<std::string> strings(const toml::node& n, std::string_view what,
                                   bool allow_empty = false) const;
  const toml::table& table(const toml::node& n, std::string_view what) const;
  // A renderer parameter as renderer::set_param takes it: a number or string as text, an
  // array as a comma-separated list.
  std::string param(const toml::node& n) const;
  // A non-empty array of tables ([[what]]).
  std::vector<const toml::table*> tables(const toml::node& n, std::string_view what) const;
  // A string that is safe as part of a file name: letters, digits, _ - . (not leading '.').
  std::string name(const toml::node& n, std::string_view what) const;

 private:
  std::filesystem::path file_;
};

}  // namespace aosuite
