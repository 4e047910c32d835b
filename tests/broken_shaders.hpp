// A deliberate regression for the harness's end-to-end tests: a copy of the shaders in which
// SAO is twice as dark. Point AOSUITE_SHADER_DIR at the folder to render with it.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "process.hpp"

namespace aosuite::test {

inline void write_broken_shaders(const std::filesystem::path& dir) {
  std::filesystem::copy(
      std::filesystem::path(AOSUITE_SOURCE_DIR) / "renderer" / "passes" / "shaders", dir);
  std::string sao = read_text(dir / "sao.glsl");
  const std::string term = "1.0 - sum * u_intensity";
  ASSERT_NE(sao.find(term), std::string::npos) << "sao.glsl changed; update this test";
  sao.replace(sao.find(term), term.size(), "1.0 - 2.0 * sum * u_intensity");
  std::ofstream(dir / "sao.glsl") << sao;
}

}  // namespace aosuite::test
