#include "renderer/passes/shader_library.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "common/content_hash.hpp"

namespace aosuite::renderer {

const std::map<std::string_view, std::string_view>& embedded_shaders();  // generated

std::string shader_text(std::string_view name) {
  if (const char* dir = std::getenv("AOSUITE_SHADER_DIR"); dir && *dir) {
    const std::filesystem::path path = std::filesystem::path(dir) / name;
    if (std::ifstream in{path, std::ios::binary}) {
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    }
  }
  const auto& files = embedded_shaders();
  const auto it = files.find(name);
  if (it == files.end()) throw std::invalid_argument("no shader named " + std::string(name));
  return std::string(it->second);
}

std::vector<std::string_view> shader_names() {
  std::vector<std::string_view> names;
  for (const auto& [name, text] : embedded_shaders()) names.push_back(name);
  return names;
}

std::string shaders_hash() {
  ContentHash h;
  for (std::string_view name : shader_names()) h.add(name).add(shader_text(name));
  return h.hex();
}

}  // namespace aosuite::renderer
