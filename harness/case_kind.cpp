#include "harness/case_kind.hpp"

#include <algorithm>

namespace aosuite::harness {
namespace {

struct Registry {
  std::vector<std::unique_ptr<CaseKind>> kinds;
  std::function<void()> loader;
  bool loaded = false;
};

Registry& registry() {
  static Registry r;
  return r;
}

template <typename Match>
const CaseKind* find_loading(Match match) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    for (const auto& k : registry().kinds)
      if (match(*k)) return k.get();
    if (!load_kinds()) break;
  }
  return nullptr;
}

}  // namespace

bool load_kinds() {
  Registry& r = registry();
  if (r.loaded || !r.loader) return false;
  r.loaded = true;
  r.loader();
  return true;
}

bool is_image_kind(std::string_view name) {
  return name == "files" || name == "command" || name == "folder";
}

void register_kind(std::unique_ptr<CaseKind> kind) {
  std::erase_if(registry().kinds, [&](const auto& k) { return k->name() == kind->name(); });
  registry().kinds.push_back(std::move(kind));
}

void set_kind_loader(std::function<void()> loader) {
  registry().loader = std::move(loader);
  registry().loaded = false;
}

const CaseKind* kind_for(const toml::table& case_table) {
  return find_loading([&](const CaseKind& k) { return case_table.contains(k.key()); });
}

const CaseKind* find_kind(std::string_view name) {
  return find_loading([&](const CaseKind& k) { return k.name() == name; });
}

std::vector<const CaseKind*> kinds() {
  std::vector<const CaseKind*> out;
  for (const auto& k : registry().kinds) out.push_back(k.get());
  return out;
}

std::vector<std::string_view> kinds_default_keys() {
  std::vector<std::string_view> out;
  for (const CaseKind* k : kinds())
    for (std::string_view key : k->default_keys()) out.push_back(key);
  return out;
}

std::vector<std::string_view> kinds_case_keys() {
  std::vector<std::string_view> out;
  for (const CaseKind* k : kinds()) {
    out.push_back(k->key());
    for (std::string_view key : k->case_keys()) out.push_back(key);
  }
  return out;
}

}  // namespace aosuite::harness
