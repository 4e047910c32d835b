#include "harness/goldens.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "compare/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::string platform_key(std::string_view description) {
  std::string_view renderer = description;
  if (const std::size_t a = description.find(" | "); a != std::string_view::npos) {
    renderer = description.substr(a + 3);
    renderer = renderer.substr(0, renderer.find(" | "));
  }
  std::string key;
  for (const char ch : renderer) {
    if (std::isalnum(static_cast<unsigned char>(ch))) {
      key += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    } else if (!key.empty() && key.back() != '-') {
      key += '-';
    }
  }
  while (!key.empty() && key.back() == '-') key.pop_back();
  return key.empty() ? "unknown" : key;
}

namespace {

// <image>.png first, then its variants <image>~<tag>.png in name order.
std::vector<fs::path> goldens_in(const fs::path& dir, std::string_view image) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    const bool primary = name == std::string(image) + ".png";
    const bool variant = name.starts_with(std::string(image) + "~") && name.ends_with(".png");
    if (primary || variant) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    const bool av = a.filename().string().find('~') != std::string::npos;
    const bool bv = b.filename().string().find('~') != std::string::npos;
    return av != bv ? bv : a < b;
  });
  return out;
}

}  // namespace

std::vector<fs::path> accepted_goldens(const fs::path& case_dir, std::string_view image,
                                       std::string_view platform) {
  std::vector<fs::path> out = goldens_in(case_dir / platform, image);
  return out.empty() ? goldens_in(case_dir, image) : out;
}

fs::path golden_path(const fs::path& case_dir, std::string_view image, std::string_view platform,
                     std::string_view tag) {
  const std::string name = fmt::format("{}{}{}.png", image, tag.empty() ? "" : "~", tag);
  return platform.empty() ? case_dir / name : case_dir / platform / name;
}

void write_golden(const fs::path& path, std::span<const unsigned char> png) {
  fs::create_directories(path.parent_path());
  write_file_atomic(path, png);
}

}  // namespace aosuite::harness
