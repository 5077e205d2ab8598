#include "quality/quality_stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vorohex::quality {
namespace {

TEST(QualityStats, EmptyInputIsAllZero) {
  const QualityStats s = quality_stats({});
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.min, 0.0);
  EXPECT_EQ(s.max, 0.0);
  EXPECT_EQ(s.mean, 0.0);
  EXPECT_EQ(s.fraction_below_0_2, 0.0);
  EXPECT_EQ(s.inverted, 0u);
  for (std::size_t b : s.histogram) EXPECT_EQ(b, 0u);
}

TEST(QualityStats, KnownVectorFillsExpectedBins) {
  const QualityStats s = quality_stats({-1.0, -0.05, 0.0, 0.15, 0.2, 0.5, 0.95, 1.0, 1.5, -2.0});
  EXPECT_EQ(s.count, 10u);
  EXPECT_DOUBLE_EQ(s.min, -2.0);
  EXPECT_DOUBLE_EQ(s.max, 1.5);
  EXPECT_NEAR(s.mean, 0.125, 1e-15);
  EXPECT_DOUBLE_EQ(s.fraction_below_0_2, 0.5);  // -1, -0.05, 0, 0.15, -2
  EXPECT_EQ(s.inverted, 4u);                    // -1, -0.05, 0, -2
  std::array<std::size_t, QualityStats::kBins> expected{};
  expected[0] = 2;   // -1 and -2 (clamped)
  expected[9] = 1;   // -0.05 in [-0.1, 0)
  expected[10] = 1;  // 0 in [0, 0.1)
  expected[11] = 1;  // 0.15
  expected[12] = 1;  // 0.2 opens [0.2, 0.3)
  expected[15] = 1;  // 0.5
  expected[19] = 3;  // 0.95, 1 (last bin) and 1.5 (clamped)
  EXPECT_EQ(s.histogram, expected);
}

TEST(QualityStats, DecimalBinEdgesLandInTheUpperBin) {
  const QualityStats s = quality_stats({-0.3, 0.3, 0.7, -0.9, 0.1});
  EXPECT_EQ(s.histogram[7], 1u);
  EXPECT_EQ(s.histogram[13], 1u);
  EXPECT_EQ(s.histogram[17], 1u);
  EXPECT_EQ(s.histogram[1], 1u);
  EXPECT_EQ(s.histogram[11], 1u);
}

TEST(QualityStats, NanCountsAsWorstElement) {
  const QualityStats s = quality_stats({std::numeric_limits<double>::quiet_NaN(), 1.0});
  EXPECT_EQ(s.inverted, 1u);
  EXPECT_EQ(s.histogram[0], 1u);
  EXPECT_EQ(s.histogram[19], 1u);
  EXPECT_DOUBLE_EQ(s.min, -1.0);
  EXPECT_DOUBLE_EQ(s.fraction_below_0_2, 0.5);
}

TEST(QualityStats, HistogramSumsToCount) {
  std::vector<double> v;
  for (int i = -150; i <= 150; ++i) v.push_back(i / 100.0);
  const QualityStats s = quality_stats(v);
  std::size_t total = 0;
  for (std::size_t b : s.histogram) total += b;
  EXPECT_EQ(total, v.size());
  EXPECT_EQ(s.inverted, 151u);  // -1.5 .. 0
  EXPECT_NEAR(s.mean, 0.0, 1e-15);
}

}  // namespace
}  // namespace vorohex::quality
