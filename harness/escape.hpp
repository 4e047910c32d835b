// Text made safe to show: in a terminal or a message (printable), in HTML and XML element
// content and attribute values (escape_markup), on a shell command line (shell_quote).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <string_view>

namespace aosuite::harness {

// `s` with every byte that is not part of well-formed UTF-8 written as \xNN, and every control
// character (C0, DEL, C1) and the non-characters U+FFFE/U+FFFF as \xNN or \uNNNN: valid UTF-8
// on one line, fit for JSON, XML 1.0 and a terminal. Valid text is unchanged.
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

// printable() line by line: text of several lines (a command's stderr) keeps its line breaks.
inline std::string printable_lines(std::string_view s) {
  std::string out;
  for (std::size_t at = 0; at <= s.size();) {
    const std::size_t nl = std::min(s.find('\n', at), s.size());
    out += printable(s.substr(at, nl - at));
    if (nl < s.size()) out += '\n';
    at = nl + 1;
  }
  return out;
}

// printable(s) with the markup characters escaped.
inline std::string escape_markup(std::string_view text) {
  const std::string s = printable(text);
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

// One shell word that a POSIX shell (bash, zsh, sh for printable text) reads back as `s`: bare
// when it holds only safe characters, else in single quotes; bytes that are not printable
// UTF-8 use bash's $'\xNN' form, so the word itself is printable ASCII.
inline std::string shell_quote(std::string_view s) {
  const auto safe = [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           std::string_view("_-./=:,+@%").find(ch) != std::string_view::npos;
  };
  if (!s.empty() && std::all_of(s.begin(), s.end(), safe)) return std::string(s);
  if (printable(s) == s) {
    std::string out = "'";
    for (const char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
  }
  std::string out = "$'";
  for (const char ch : s) {
    const auto b = static_cast<unsigned char>(ch);
    if (b < 0x20 || b >= 0x7F) {
      out += fmt::format("\\x{:02x}", b);
    } else if (ch == '\'' || ch == '\\') {
      out += std::string("\\") + ch;
    } else {
      out += ch;
    }
  }
  return out + "'";
}

}  // namespace aosuite::harness
