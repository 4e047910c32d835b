#include "harness/suite.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "harness/escape.hpp"
#include "harness/invocation.hpp"
#include "image/picture.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::map<std::string, std::string> command_placeholders(const Case& k) {
  std::map<std::string, std::string> v;
  for (const auto& [key, value] : k.param_overrides) v[key] = value;
  v["id"] = k.id, v["name"] = k.id, v["suite_dir"] = k.source->dir.string();
  if (k.width > 0) v["width"] = std::to_string(k.width), v["height"] = std::to_string(k.height);
  return v;
}

std::string expand_placeholders(std::string_view text,
                                const std::map<std::string, std::string>& values, bool quote) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if ((ch == '{' || ch == '}') && i + 1 < text.size() && text[i + 1] == ch) {
      out += ch, ++i;
      continue;
    }
    if (ch != '{') {
      out += ch;
      continue;
    }
    const std::size_t end = text.find('}', i);
    const std::string key(text.substr(i + 1, end == std::string_view::npos ? 0 : end - i - 1));
    const auto it = values.find(key);
    if (end == std::string_view::npos || it == values.end()) {
      std::string known;
      for (const auto& [k, v] : values) known += (known.empty() ? "" : ", ") + ("{" + k + "}");
      throw std::invalid_argument(
          "unknown placeholder '" +
          printable(text.substr(i, end == std::string_view::npos ? text.size() - i : end - i + 1)) +
          "' (known: " + known + "; write {{ for a brace)");
    }
    out += quote ? shell_quote(it->second) : it->second;
    i = end;
  }
  return out;
}

fs::path region_map(const fs::path& golden, std::string_view image) {
  return golden.parent_path() / (std::string(image) + ".regions.png");
}

std::string name_problem(std::string_view id) {
  if (id.empty()) return "is empty";
  if (id.size() > kMaxNameLength) {
    return fmt::format("is {} characters long, over the {} a name may have (it names a folder)",
                       id.size(), kMaxNameLength);
  }
  if (id.front() == '.') return "starts with '.'";
  const bool allowed = std::all_of(id.begin(), id.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           ch == '-' || ch == '_' || ch == '.';
  });
  return allowed ? "" : "may hold only letters, digits, - _ . and not start with '.'";
}

bool valid_name(std::string_view id) { return name_problem(id).empty(); }

Suite folder_suite(const fs::path& actual, const fs::path& expected, const Tolerance& tolerance) {
  // Relative path -> whether it is in actual, in expected.
  std::map<std::string, std::pair<bool, bool>> paths;
  std::vector<Skipped> skipped;
  std::set<std::string> skipped_actual;  // there, but not read: never "deleted"
  auto scan = [&](const fs::path& root, bool is_actual) {
    std::error_code ec;
    if (!fs::is_directory(root, ec)) {
      throw std::runtime_error(root.string() + ": not a folder" +
                               (ec ? " (" + ec.message() + ")" : std::string()));
    }
    // Links are never followed (a link may lead out of the folder, to a device, or to
    // itself): each is skipped and said, as is every file that is not a PNG or EXR image.
    fs::recursive_directory_iterator it(root, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
      const std::string rel = it->path().lexically_relative(root).generic_string();
      if (rel.empty() || rel.front() == '.') {
        if (it->is_directory(ec)) it.disable_recursion_pending();
        ec.clear();
        continue;
      }
      const fs::file_status st = it->symlink_status(ec);
      const auto skip = [&](std::string why) {
        skipped.push_back({(root / rel).generic_string(), std::move(why)});
        if (is_actual) skipped_actual.insert(rel);
      };
      if (ec) {
        skip(ec.message());
        ec.clear();
      } else if (fs::is_symlink(st)) {
        skip("a symbolic link (not followed)");
      } else if (fs::is_directory(st)) {
        continue;
      } else if (!fs::is_regular_file(st)) {
        skip("not a regular file");
      } else if (!is_image_name(it->path())) {
        skip("not an image file");
      } else {
        (is_actual ? paths[rel].first : paths[rel].second) = true;
      }
    }
    if (ec) throw std::runtime_error(root.string() + ": cannot be read: " + ec.message());
  };
  scan(actual, true);
  scan(expected, false);
  Suite suite;
  suite.skipped = std::move(skipped);
  suite.name = "folder";
  suite.file = actual;
  suite.goldens = expected;
  suite.goldens_given = true;
  suite.expected = expected;
  suite.bless_prefix = program_command() + " bless --actual " + shell_quote(actual.string()) +
                       " --expected " + shell_quote(expected.string());
  suite.check_args =
      "--actual " + shell_quote(actual.string()) + " --expected " + shell_quote(expected.string());
  std::map<std::string, std::string> ids;
  for (const auto& [rel, where] : paths) {
    // An actual image that was skipped (a link, not a regular file) is not a deleted one: its
    // expected image is left out too, never judged missing nor removed by bless.
    if (!where.first && skipped_actual.count(rel)) {
      suite.skipped.push_back(
          {(expected / rel).generic_string(), "its actual file was skipped; left as it is"});
      continue;
    }
    // sub/dir/a b.png -> sub__dir__a_b.png: a name for the report's folder.
    std::string id;
    for (const char ch : rel) {
      id += ch == '/'                                     ? std::string("__")
            : valid_name(std::string(1, ch)) || ch == '.' ? std::string(1, ch)
                                                          : std::string("_");
    }
    if (id.front() == '.') id.front() = '_';
    if (!valid_name(id)) {
      throw std::runtime_error(printable((actual / rel).string()) + ": path too long for a case");
    }
    if (const auto [it, fresh] = ids.emplace(id, rel); !fresh) {
      throw std::runtime_error(printable(
          fmt::format("{} and {} both become case '{}'; rename one", it->second, rel, id)));
    }
    auto src = std::make_shared<ImageSource>();
    src->path = rel;
    src->golden_file = expected / rel;
    src->files.push_back(actual / rel);
    src->deleted = !where.first;
    src->exts["image"] = fs::path(rel).extension().string();
    Case k;
    k.id = id;
    k.images = {"image"};
    k.tolerance = tolerance;
    k.source = std::move(src);
    k.table = static_cast<int>(suite.cases.size());
    suite.cases.push_back(std::move(k));
  }
  return suite;
}

}  // namespace aosuite::harness
