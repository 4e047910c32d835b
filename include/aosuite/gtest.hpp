// GoogleTest assertions over aosuite's golden comparison: a failure prints the verdict (the
// limits that failed, the failure images' paths, the golden's path and how to accept it), and
// the failure images go into a folder named after the running test.
//
//   #include <aosuite/gtest.hpp>
//   TEST(Frame, Matches) { EXPECT_MATCHES_GOLDEN(render(), "goldens/frame.png"); }
//   EXPECT_MATCHES_GOLDEN(render(), "goldens/frame.png", {.max_mismatch_percent = 0.1});
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "aosuite/aosuite.hpp"

namespace aosuite::testing {

// "Suite.Test" of the running test, or "" outside one.
inline std::string current_test() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return info ? std::string(info->test_suite_name()) + "." + info->name() : std::string();
}

template <class Img>
::testing::AssertionResult MatchesGolden(const Img& image, const std::string& golden,
                                         const Tolerance& tolerance = {}) {
  const Verdict v = matches_golden(image, golden, tolerance, current_test());
  if (v) return ::testing::AssertionSuccess() << v;
  std::ostringstream why;
  why << golden << ": " << v;
  return ::testing::AssertionFailure() << why.str();
}

}  // namespace aosuite::testing

#define EXPECT_MATCHES_GOLDEN(image, golden, ...) \
  EXPECT_TRUE(::aosuite::testing::MatchesGolden((image), (golden)__VA_OPT__(, ) __VA_ARGS__))
#define ASSERT_MATCHES_GOLDEN(image, golden, ...) \
  ASSERT_TRUE(::aosuite::testing::MatchesGolden((image), (golden)__VA_OPT__(, ) __VA_ARGS__))
