// Text made safe to show: in a terminal or a message (printable), in HTML and XML element
// content and attribute values (escape_markup), on a shell command line (shell_quote).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "common/printable.hpp"

namespace aosuite::harness {

// printable(s): common/printable.hpp (shared with the renderer's messages).
using aosuite::printable;

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

// JSON to embed in a <script type="application/json"> element: no byte sequence of any string
// in it can end the element or change how the HTML parser reads it (`</script>`, `<!--` then
// `<script>`, which sends the parser into its "double escaped" state, where the element's end
// tag no longer ends it). `<`, `>` and `&` only occur inside JSON strings, where \u003c,
// \u003e and \u0026 mean the same characters to JSON.parse.
inline std::string json_in_script(const nlohmann::json& j) {
  const std::string text = j.dump();
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else {
      out += c;
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
