#include "compare/tolerance.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace aosuite::comparison {

namespace {

double number(std::string_view key, const std::string& text, double lo, double hi) {
  char* end = nullptr;
  errno = 0;
  const double v = text.empty() ? NAN : std::strtod(text.c_str(), &end);
  if (!std::isfinite(v) || end != text.c_str() + text.size() || errno == ERANGE) {
    throw std::invalid_argument(fmt::format("{} = '{}' is not a number", key, text));
  }
  if (v < lo || v > hi) {
    throw std::invalid_argument(fmt::format("{} must be {:g}..{:g} (not {})", key, lo, hi, text));
  }
  return v;
}

long long whole(std::string_view key, const std::string& text, double lo, double hi) {
  const double v = number(key, text, lo, hi);
  if (v != std::floor(v))
    throw std::invalid_argument(fmt::format("{} = {} is not whole", key, text));
  return static_cast<long long>(v);
}

bool boolean(std::string_view key, const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  throw std::invalid_argument(fmt::format("{} = '{}' is not true or false", key, text));
}

}  // namespace

void set_limit(Tolerance& t, std::string_view key, const std::string& value) {
  if (key == "mode") {
    t.mode = resemble::parse_mode(value);
  } else if (key == "max_mismatch_percent") {
    t.max_mismatch_percent = number(key, value, 0, 100);
  } else if (key == "max_channel_delta") {
    t.max_channel_delta = int(whole(key, value, 0, 255));
    t.min_channel_delta = std::min(t.min_channel_delta, t.max_channel_delta);
  } else if (key == "max_differing_pixels") {
    t.max_differing_pixels = whole(key, value, 0, 1 << 30);
  } else if (key == "max_mean_shift") {
    t.max_mean_shift = number(key, value, 0, 255);
  } else if (key == "max_mean_delta") {
    t.max_mean_delta = number(key, value, 0, 255);
  } else if (key == "shift_radius") {
    t.shift_radius = int(whole(key, value, 0, 16));
  } else if (key == "allow_kind_change") {
    t.allow_kind_change = boolean(key, value);
  } else if (key == "resemble") {
    t.resemble = boolean(key, value);
  } else {
    throw std::invalid_argument(fmt::format("unknown limit '{}' ({})", key, kLimitKeys));
  }
}

}  // namespace aosuite::comparison
