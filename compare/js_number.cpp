#include "compare/js_number.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace aosuite {

std::string js_to_fixed2(double x) {
  if (std::isnan(x)) return "NaN";
  if (std::abs(x) >= 1e21) return js_number_to_string(x);
  // glibc prints the exact decimal expansion of a double; a double below 1e21 has at most
  // 1074 fraction digits, so three digits decide: the third >= 5 means round up (a tie,
  // "5" followed by zeros, rounds up too, as the spec's "pick the larger n").
  std::array<char, 1200> buf{};
  const double ax = std::abs(x);
  const int n = std::snprintf(buf.data(), buf.size(), "%.1100f", ax);
  if (n <= 0) throw std::runtime_error("js_to_fixed2: formatting failed");
  std::string s(buf.data(), static_cast<std::size_t>(n));
  const std::size_t dot = s.find('.');
  std::string kept = s.substr(0, dot + 3);
  if (s[dot + 3] >= '5') {
    // Increment the decimal string kept, carrying through the dot.
    int i = static_cast<int>(kept.size()) - 1;
    for (; i >= 0; --i) {
      if (kept[i] == '.') continue;
      if (kept[i] == '9') {
        kept[i] = '0';
      } else {
        ++kept[i];
        break;
      }
    }
    if (i < 0) kept.insert(kept.begin(), '1');
  }
  // JS prints "-0.00" for small negatives too ((-0.001).toFixed(2) === "-0.00").
  if (std::signbit(x) && x != 0.0) kept.insert(0, 1, '-');
  return kept;
}

std::string js_number_to_string(double x) {
  if (std::isnan(x)) return "NaN";
  if (std::isinf(x)) return x > 0 ? "Infinity" : "-Infinity";
  if (x == 0.0) return "0";
  // Shortest round-trip digits in scientific form: d[.ddd]e[+-]N.
  std::array<char, 64> buf{};
  auto res = std::to_chars(buf.data(), buf.data() + buf.size(), std::abs(x),
                           std::chars_format::scientific);
  std::string sci(buf.data(), res.ptr);
  const std::size_t e = sci.find('e');
  std::string digits;
  for (std::size_t i = 0; i < e; ++i) {
    if (sci[i] != '.') digits += sci[i];
  }
  const int k = static_cast<int>(digits.size());
  const int n = std::atoi(sci.c_str() + e + 1) + 1;  // x = 0.digits * 10^n
  std::string out = x < 0 ? "-" : "";
  if (k <= n && n <= 21) {
    out += digits + std::string(static_cast<std::size_t>(n - k), '0');
  } else if (0 < n && n <= 21) {
    out.append(digits, 0, static_cast<std::size_t>(n))
        .append(".")
        .append(digits, static_cast<std::size_t>(n));
  } else if (-6 < n && n <= 0) {
    out.append("0.").append(static_cast<std::size_t>(-n), '0').append(digits);
  } else {
    out += digits.substr(0, 1);
    if (k > 1) out.append(".").append(digits, 1);
    out.append(n - 1 >= 0 ? "e+" : "e-").append(std::to_string(std::abs(n - 1)));
  }
  return out;
}

}  // namespace aosuite
