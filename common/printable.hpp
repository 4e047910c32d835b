// Text made safe to show in a terminal or a one-line message: every byte that is not part of
// well-formed UTF-8 and every control character written as an escape. The lowest layer, so
// every library (compare, renderer, harness) quotes file content and paths through it.
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

namespace aosuite {

// `s` with every byte that is not part of well-formed UTF-8 written as \xNN, and every control
// character (C0, DEL, C1) and the non-characters U+FFFE/U+FFFF as \xNN or \uNNNN: valid UTF-8
// on one line, fit for JSON, XML 1.0 and a terminal. Valid text is unchanged, so escaping
// twice changes nothing.
inline std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    const std::size_t n = b < 0x80           ? 1
                          : (b >> 5) == 0x6  ? 2
                          : (b >> 4) == 0xE  ? 3
                          : (b >> 3) == 0x1E ? 4
                                             : 0;
    char32_t cp = n == 1 ? b : n == 2 ? (b & 0x1Fu) : n == 3 ? (b & 0x0Fu) : (b & 0x07u);
    bool ok = n != 0 && i + n <= s.size();
    for (std::size_t k = 1; ok && k < n; ++k) {
      const auto c = static_cast<unsigned char>(s[i + k]);
      ok = (c & 0xC0) == 0x80;
      cp = (cp << 6) | (c & 0x3Fu);
    }
    if (ok) {
      constexpr char32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};  // shorter forms are overlong
      ok = cp >= kLeast[n] && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF);
    }
    if (!ok) {
      out += fmt::format("\\x{:02x}", b);
      ++i;
    } else if (cp < 0x20 || cp == 0x7F) {
      out += fmt::format("\\x{:02x}", static_cast<unsigned>(cp));
      i += n;
    } else if ((cp >= 0x80 && cp <= 0x9F) || cp == 0xFFFE || cp == 0xFFFF) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned>(cp));
      i += n;
    } else {
      out.append(s.substr(i, n));
      i += n;
    }
  }
  return out;
}

}  // namespace aosuite
