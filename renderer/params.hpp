// The parameter table: every key that `--param`, suites and sweep grids accept, which field of
// AoParams it sets, its range, which techniques read it, and its doc line. Parsing,
// validation, help text, the harness's input hash, render JSON and results.json iterate it,
// so a new parameter is one row here (and its field in technique.hpp).
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "renderer/technique.hpp"

namespace aosuite::renderer {

// A parameter's value with its type, for JSON.
using ParamValue = std::variant<int, float, std::string, std::vector<float>>;

// Where `aosuite tune` searches a number (each weight of a list), `log`: evenly in its
// logarithm. lo == hi: not searched (the radius is the study's, not the tuner's; cost caps).
struct SearchRange {
  double lo = 0, hi = 0;
  bool log = false;
  bool searched() const { return hi > lo; }
};

struct ParamSpec {
  std::string_view key;
  std::string_view doc;
  bool (*reads)(const TechniqueInfo&);  // whether a technique's pass reads it
  // Where it lives in AoParams.
  std::variant<int& (*)(AoParams&), float& (*)(AoParams&), Blur& (*)(AoParams&),
               std::array<float, 5>& (*)(AoParams&)>
      field;
  double min, max;     // inclusive range of the number (each weight); unused for blur
  bool min_exclusive;  // e.g. radius > 0
  // A valid value unlike every technique's default: what tests set to see it change a hash.
  std::string_view sample;
  SearchRange search;
};

std::span<const ParamSpec> param_specs();
const ParamSpec& param_spec(std::string_view key);  // throws std::invalid_argument
bool applies(const ParamSpec& spec, Technique t);
std::vector<std::string_view> param_names();

// Sets one parameter from text, as suites and `--param key=value` give them, and checks its
// range. Throws std::invalid_argument naming the key and the problem (unknown key, not a
// number, non-finite, out of range).
void set_param(AoParams& params, std::string_view key, std::string_view value);
// Checks every parameter's range and the cross-field rules; throws std::invalid_argument.
void check_params(const AoParams& params);

ParamValue param_value(const ParamSpec& spec, const AoParams& params);
// The value as set_param reads it back ("1,0.5,0.3,0.3,0.3" for a list).
std::string param_text(const ParamSpec& spec, const AoParams& params);

}  // namespace aosuite::renderer
