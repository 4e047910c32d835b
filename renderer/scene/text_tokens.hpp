// Whitespace-separated tokens of a mesh file's text, with the line each is on, for the
// readers and structure checks of the text formats (mesh_check.cpp, stl_mesh.cpp).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <optional>
#include <string_view>

#include "common/file_io.hpp"
#include "common/printable.hpp"

namespace aosuite::renderer::text {

template <typename T>
std::optional<T> parse(std::string_view t);

// Whitespace-separated tokens of a text, with the line each is on.
class Tokens {
 public:
  // `comment`: a character that starts a comment running to the end of its line (0: none).
  Tokens(std::string_view name, std::string_view text, char comment = 0)
      : name_(name), text_(text), comment_(comment) {}

  // The next token, or empty at the end of the text.
  std::string_view next() {
    for (;;) {
      while (pos_ < text_.size() && is_space(text_[pos_])) line_ += text_[pos_++] == '\n';
      if (!comment_ || pos_ == text_.size() || text_[pos_] != comment_) break;
      rest_of_line();
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  // The rest of the current line, consumed with its newline.
  std::string_view rest_of_line() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    const std::string_view rest = text_.substr(pos_, end - pos_);
    pos_ = end;
    return rest;
  }
  std::size_t offset() const { return pos_; }
  void seek(std::size_t pos) { pos_ = pos; }
  int line() const { return line_; }
  // The next token as a number; `what()` describes it for a message (made only on failure).
  template <typename T, typename What>
  T number(What&& what) {
    const std::string_view t = next();
    if (t.empty()) fail(fmt::format("truncated: {} missing", what()));
    const std::optional<T> v = parse<T>(t);
    if (!v) fail(fmt::format("'{}' is not a valid {}", t.substr(0, 64), what()));
    return *v;
  }
  [[noreturn]] void fail(std::string_view why) const { fail_at(line_, why); }
  // Messages quote the file's bytes: escaped (\xNN), never raw.
  [[noreturn]] void fail_at(int line, std::string_view why) const {
    throw FileError(printable(fmt::format("{}:{}: {}", name_, line, why)));
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  std::string_view name_, text_;
  char comment_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// A whole token as a number (no sign for unsigned types), or nothing.
template <typename T>
std::optional<T> parse(std::string_view t) {
  T v{};
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size() || t.empty()) return std::nullopt;
  return v;
}

}  // namespace aosuite::renderer::text
