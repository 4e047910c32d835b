// The AO studies' small statistics against values worked out by hand: the median of odd and
// even counts, Pearson's correlation of exact lines and constants, and ranks with ties.
#include "ao/statistics.hpp"

#include <gtest/gtest.h>

namespace aosuite::ao {
namespace {

TEST(Statistics, TheMedianOfAnEvenCountIsTheMeanOfTheMiddleTwo) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({3.0}), 3.0);
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 10.0}), 3.5);
  EXPECT_EQ(median({2.0, 1.0}), 1.5);
}

TEST(Statistics, PearsonIsOneOnALineMinusOneReversedAndZeroOnAConstant) {
  EXPECT_NEAR(pearson({1, 2, 3, 4}, {3, 5, 7, 9}), 1.0, 1e-12);
  EXPECT_NEAR(pearson({1, 2, 3, 4}, {8, 6, 4, 2}), -1.0, 1e-12);
  EXPECT_EQ(pearson({1, 2, 3}, {5, 5, 5}), 0.0);
}

TEST(Statistics, TiedValuesShareTheirMeanRank) {
  EXPECT_EQ(ranks({10, 30, 20}), (std::vector<double>{0, 2, 1}));
  EXPECT_EQ(ranks({7, 7, 1, 9, 7}), (std::vector<double>{2, 2, 0, 4, 2}));
  EXPECT_EQ(ranks({5, 5}), (std::vector<double>{0.5, 0.5}));
}

}  // namespace
}  // namespace aosuite::ao
