// A suite file written into a temporary folder and read back: what tests of suite parsing share
// (harness_test.cpp's image cases, ao_cases_test.cpp's scene cases).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "harness/suite_file.hpp"
#include "png_fixture.hpp"

namespace aosuite::test {

class SuiteFile : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& text) {
    const std::filesystem::path file = dir_ / "suites" / "s.toml";
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file;
  }
  // The message load_suite throws for `text`, or "" if it loads.
  std::string error_of(const std::string& text) {
    try {
      harness::load_suite(write(text));
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  TempDir dir_;
};

}  // namespace aosuite::test
