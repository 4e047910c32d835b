// Where aosuite keeps what it downloads and caches (meshes, ray-traced references): the
// repository's .cache when run from a build of a checkout (the folder the build names exists),
// else the user's cache folder ($XDG_CACHE_HOME/aosuite, else ~/.cache/aosuite), as an
// installed aosuite runs. Header-only.
#pragma once

#include <cstdlib>
#include <filesystem>

namespace aosuite {

// `built_in`: the checkout's .cache as the build named it (its parent, the checkout, must exist).
inline std::filesystem::path cache_dir(const std::filesystem::path& built_in) {
  std::error_code ec;
  if (std::filesystem::is_directory(built_in.parent_path(), ec)) return built_in;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "aosuite";
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home && *home ? home : "/tmp") / ".cache" / "aosuite";
}

}  // namespace aosuite
