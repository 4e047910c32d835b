// Entry points of the libraries that lie beside the `aosuite` executable and are opened only
// when needed: libaosuite_gl.so (OpenGL commands, by the launcher) and libaosuite_exr.so
// (OpenImageIO, by write_exr). Header-only: the launcher links neither library.
#pragma once

#include <dlfcn.h>

#include <filesystem>
#include <string>

namespace aosuite {

// `symbol` of `library` in the executable's directory, as a function of type Fn; nullptr,
// with dlerror()'s reason (it names the file or the symbol) in `error`, when either is missing.
template <class Fn>
Fn* sibling_symbol(const char* library, const char* symbol, std::string& error) {
  const std::filesystem::path path =
      std::filesystem::read_symlink("/proc/self/exe").parent_path() / library;
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  void* found = handle ? dlsym(handle, symbol) : nullptr;
  if (!found) error = dlerror();
  return reinterpret_cast<Fn*>(found);
}

}  // namespace aosuite
