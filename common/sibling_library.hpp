// Entry points of the libraries that lie beside the `aosuite` executable (in a build folder) or
// in ../AOSUITE_PLUGIN_DIR from it (installed), opened only when needed: libaosuite_check.so and
// libaosuite_gl.so (commands, by the launcher), libaosuite_exr.so (OpenEXR, by write_exr),
// libaosuite_oiio.so (other formats). Header-only: the launcher links none of them.
#pragma once

#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <vector>

// Where `cmake --install` puts the plugins, relative to the prefix: lib/<multiarch>/aosuite on
// Debian. CMakeLists.txt defines it for each file that includes this (one value everywhere:
// sibling_library_path is inline).
#ifndef AOSUITE_PLUGIN_DIR
#error "AOSUITE_PLUGIN_DIR is defined by CMakeLists.txt for the files that include this"
#endif

namespace aosuite {

// Where `library` is: beside the executable, else in ../AOSUITE_PLUGIN_DIR from it (where
// `cmake --install` puts it), else in aosuite/ beside the shared library holding this code
// (libaosuite.so, find_package(aosuite), in another program), else beside that library (a
// build folder's libaosuite.so, linked by another program's tests). The executable's own
// folder is tried first, so a build folder never picks up an installed copy.
inline std::filesystem::path sibling_library_path(const char* library) {
  namespace fs = std::filesystem;
  const fs::path bin = fs::read_symlink("/proc/self/exe").parent_path();
  std::vector<fs::path> places{bin / library, bin / ".." / AOSUITE_PLUGIN_DIR / library};
  Dl_info self{};
  if (dladdr(reinterpret_cast<const void*>(&sibling_library_path), &self) && self.dli_fname) {
    const fs::path holder = fs::path(self.dli_fname).parent_path();
    places.push_back(holder / "aosuite" / library);
    places.push_back(holder / library);
  }
  std::error_code ec;
  for (const fs::path& p : places)
    if (fs::exists(p, ec)) return p.lexically_normal();
  return places.front();
}

// `symbol` of `library` (sibling_library_path), as a function of type Fn; nullptr, with
// dlerror()'s reason (it names the file or the symbol) in `error`, when either is missing.
template <class Fn>
Fn* sibling_symbol(const char* library, const char* symbol, std::string& error) {
  const std::filesystem::path path = sibling_library_path(library);
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  void* found = handle ? dlsym(handle, symbol) : nullptr;
  if (!found) error = dlerror();
  return reinterpret_cast<Fn*>(found);
}

}  // namespace aosuite
