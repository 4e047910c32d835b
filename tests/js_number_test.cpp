#include "compare/js_number.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace aosuite {
namespace {

TEST(JsToFixed2, ExactTiesRoundUp) {
  EXPECT_EQ(js_to_fixed2(3.125), "3.13");  // printf's round-half-even gives "3.12"
  EXPECT_EQ(js_to_fixed2(0.125), "0.13");
  EXPECT_EQ(js_to_fixed2(0.375), "0.38");
}

TEST(JsToFixed2, TheBinaryValueDecides) {
  EXPECT_EQ(js_to_fixed2(1.005), "1.00");     // 1.00499999999999989...
  EXPECT_EQ(js_to_fixed2(1.045), "1.04");     // 1.04499999999999992...
  EXPECT_EQ(js_to_fixed2(0.005), "0.01");     // 0.00500000000000000010...
  EXPECT_EQ(js_to_fixed2(99.995), "100.00");  // 99.99500000000000454...
  EXPECT_EQ(js_to_fixed2(2.675), "2.67");     // 2.67499999999999982...
  EXPECT_EQ(js_to_fixed2(99.996), "100.00");
  EXPECT_EQ(js_to_fixed2(6.0 / 9.0 * 100), "66.67");
}

TEST(JsToFixed2, PlainValues) {
  EXPECT_EQ(js_to_fixed2(0), "0.00");
  EXPECT_EQ(js_to_fixed2(100), "100.00");
  EXPECT_EQ(js_to_fixed2(9.999), "10.00");
  EXPECT_EQ(js_to_fixed2(-0.001), "-0.00");
  EXPECT_EQ(js_to_fixed2(std::numeric_limits<double>::quiet_NaN()), "NaN");
}

TEST(JsNumberToString, ShortestRoundTrip) {
  EXPECT_EQ(js_number_to_string(6.0 / 9.0 * 100), "66.66666666666666");
  EXPECT_EQ(js_number_to_string(100), "100");
  EXPECT_EQ(js_number_to_string(0), "0");
  EXPECT_EQ(js_number_to_string(0.0244140625), "0.0244140625");
  EXPECT_EQ(js_number_to_string(205.0 / 4096 * 100), "5.0048828125");
  EXPECT_EQ(js_number_to_string(0.1 + 0.2), "0.30000000000000004");
}

TEST(JsNumberToString, ExponentFormsFollowEcmaScript) {
  EXPECT_EQ(js_number_to_string(0.000001), "0.000001");
  EXPECT_EQ(js_number_to_string(1e-7), "1e-7");
  EXPECT_EQ(js_number_to_string(1.5e-7), "1.5e-7");
  EXPECT_EQ(js_number_to_string(1.2345678901234568e20), "123456789012345680000");
  EXPECT_EQ(js_number_to_string(1e21), "1e+21");
  EXPECT_EQ(js_number_to_string(-2.5), "-2.5");
  EXPECT_EQ(js_number_to_string(std::numeric_limits<double>::infinity()), "Infinity");
}

}  // namespace
}  // namespace aosuite
