// The small statistics the AO studies share: the median of timed runs, and Pearson's and
// Spearman's correlation (the latter as Pearson's of ranks).
#pragma once

#include <vector>

namespace aosuite::ao {

// 0 for no values; the mean of the middle two for an even count.
double median(std::vector<double> v);

// 0 when either side is constant (no correlation to speak of).
double pearson(const std::vector<double>& a, const std::vector<double>& b);

// Ranks with ties given their mean rank (Spearman's correlation is Pearson's of these).
std::vector<double> ranks(const std::vector<double>& v);

}  // namespace aosuite::ao
