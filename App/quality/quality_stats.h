// Summary statistics of a per-element quality measure.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace vorohex::quality {

struct QualityStats {
  static constexpr int kBins = 20;  // histogram of [-1, 1] in bins of 0.1

  std::size_t count = 0;
  double min = 0, max = 0, mean = 0;
  std::array<std::size_t, kBins> histogram{};  // bin i covers [-1 + 0.1 i, -1 + 0.1 (i+1))
  double fraction_below_0_2 = 0;               // share of elements with value < 0.2
  std::size_t inverted = 0;                    // elements with value <= 0
};

QualityStats quality_stats(const std::vector<double>& values);

}  // namespace vorohex::quality
