#include "quality/quality_stats.h"

#include <algorithm>
#include <cmath>

namespace vorohex::quality {
namespace {

// Bin of a value in [-1, 1]: values outside clamp into the end bins, 1 goes in the last.
// Decimal inputs such as 0.3 sit a rounding error below their edge after * 10; snapping
// within 1e-9 (of a bin width) keeps them in the bin a person expects.
int bin_of(double v) {
  const double t = std::clamp(v, -1.0, 1.0) * 10.0;
  const double r = std::round(t);
  const double f = std::abs(t - r) < 1e-9 ? r : std::floor(t);
  return std::clamp(static_cast<int>(f) + 10, 0, QualityStats::kBins - 1);
}

}  // namespace

QualityStats quality_stats(const std::vector<double>& values) {
  QualityStats s;
  if (values.empty()) return s;
  s.count = values.size();
  s.min = 1.0;
  s.max = -1.0;
  double sum = 0;
  std::size_t below = 0;
  bool first = true;
  for (double raw : values) {
    // A value that is not a number is the worst possible element, never a good one.
    const double v = std::isnan(raw) ? -1.0 : raw;
    if (first) {
      s.min = s.max = v;
      first = false;
    }
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    sum += v;
    if (v < 0.2) ++below;
    if (v <= 0) ++s.inverted;
    ++s.histogram[bin_of(v)];
  }
  s.mean = sum / static_cast<double>(s.count);
  s.fraction_below_0_2 = static_cast<double>(below) / static_cast<double>(s.count);
  return s;
}

}  // namespace vorohex::quality
