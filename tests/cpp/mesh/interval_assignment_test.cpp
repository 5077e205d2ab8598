#include "mesh/interval_assignment.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

namespace vorohex::mesh {
namespace {

int sum(const std::vector<int>& n, const std::vector<int>& curves) {
  int s = 0;
  for (int c : curves) s += n[c];
  return s;
}

TEST(IntervalAssignment, UnconstrainedCurvesGetTheirRoundedTargets) {
  IntervalProblem p;
  p.add_curve(1.0, "Edge1");   // 4
  p.add_curve(2.6, "Edge2");   // 10.4 -> 10
  p.add_curve(0.05, "Edge3");  // 0.2 -> at least 1
  IntervalOptions o;
  o.size = 0.25;
  const IntervalResult r = assign_intervals(p, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.status, IntervalStatus::optimal);
  EXPECT_EQ(r.intervals, (std::vector<int>{4, 10, 1}));
}

// A mapped face 3 x 1 whose opposite sides differ in length (a trapezoid 3 / 2 over 1):
// the counts of opposite sides are equal and lie between the two targets.
TEST(IntervalAssignment, OppositeSidesOfAMappedFaceAreEqual) {
  IntervalProblem p;
  const int a = p.add_curve(3, "Edge1"), b = p.add_curve(1, "Edge2");
  const int c = p.add_curve(2, "Edge3"), d = p.add_curve(1.2, "Edge4");
  p.equal.push_back({{a}, {c}, "Face1: Edge1 opposite Edge3"});
  p.equal.push_back({{b}, {d}, "Face1: Edge2 opposite Edge4"});
  IntervalOptions o;
  o.size = 0.5;
  const IntervalResult r = assign_intervals(p, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.intervals[a], r.intervals[c]);
  EXPECT_EQ(r.intervals[b], r.intervals[d]);
  EXPECT_GE(r.intervals[a], 4);
  EXPECT_LE(r.intervals[a], 6);
  EXPECT_GE(r.intervals[b], 2);
  EXPECT_LE(r.intervals[b], 3);
}

// Sums (a submapped side) and parity (a loop meshed with unstructured quads).
TEST(IntervalAssignment, SumsAndParityHold) {
  IntervalProblem p;
  const int a = p.add_curve(1.0, "Edge1"), b = p.add_curve(1.0, "Edge2");
  const int c = p.add_curve(2.0, "Edge3"), d = p.add_curve(0.3, "Edge4");
  p.equal.push_back({{a, b}, {c}, "Face2: one side is two edges"});
  p.even.push_back({{a, b, c, d}, "Face3: loop of quads"});
  p.at_least.push_back({{a, b, c, d}, 16, "Face3: at least 16 segments"});
  IntervalOptions o;
  o.size = 0.3;
  const IntervalResult r = assign_intervals(p, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.intervals[a] + r.intervals[b], r.intervals[c]);
  EXPECT_EQ(sum(r.intervals, {a, b, c, d}) % 2, 0);
  EXPECT_GE(sum(r.intervals, {a, b, c, d}), 16);  // targets alone give 3 + 3 + 7 + 1 = 14
  for (int n : r.intervals) EXPECT_GE(n, 1);
}

// a + b == c together with a == c cannot hold with b >= 1: the error names the two
// constraints and leaves out the one that does not take part (d == e).
TEST(IntervalAssignment, InfeasibleSystemNamesTheConflictingConstraints) {
  IntervalProblem p;
  const int a = p.add_curve(1, "Edge1"), b = p.add_curve(1, "Edge2"), c = p.add_curve(2, "Edge3");
  const int d = p.add_curve(1, "Edge4"), e = p.add_curve(1, "Edge5");
  p.equal.push_back({{d}, {e}, "Face9: Edge4 opposite Edge5"});
  p.equal.push_back({{a, b}, {c}, "Face1: Edge1+Edge2 opposite Edge3"});
  p.equal.push_back({{a}, {c}, "Face2: Edge1 opposite Edge3"});
  const IntervalResult r = assign_intervals(p, IntervalOptions{});
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(r.intervals.empty());
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].code, "intervals_infeasible");
  EXPECT_NE(r.diagnostics[0].message.find("Face1"), std::string::npos);
  EXPECT_NE(r.diagnostics[0].message.find("Face2"), std::string::npos);
  EXPECT_EQ(r.diagnostics[0].message.find("Face9"), std::string::npos);
  EXPECT_EQ(r.diagnostics[0].entities, (std::vector<std::string>{"Edge1", "Edge2", "Edge3"}));
}

TEST(IntervalAssignment, MaxIntervalsBoundsEveryCurve) {
  IntervalProblem p;
  p.add_curve(100, "Edge1");
  IntervalOptions o;
  o.size = 0.1;
  o.max_intervals = 50;
  const IntervalResult r = assign_intervals(p, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.intervals[0], 50);
}

// Local sizes give targets of their own; an equality with unrefined curves keeps the
// refined count (missing it from below costs more), and a curve without a target keeps
// length / size.
TEST(IntervalAssignment, TargetsFromLocalSizesWinAnEqualityWithUnrefinedCurves) {
  IntervalProblem p;
  const int refined = p.add_curve(10, "Edge1", 19.0);
  std::vector<int> others;
  for (int k = 2; k <= 4; ++k) others.push_back(p.add_curve(10, "Edge" + std::to_string(k)));
  for (int c : others) p.equal.push_back({{refined}, {c}, "parallel edges"});
  const int free = p.add_curve(7, "Edge5");
  IntervalOptions o;
  o.size = 1;
  const IntervalResult r = assign_intervals(p, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.intervals[refined], 19);
  for (int c : others) EXPECT_EQ(r.intervals[c], 19);
  EXPECT_EQ(r.intervals[free], 7);
  EXPECT_DOUBLE_EQ(p.target(free, 1.0), 7.0);
  EXPECT_DOUBLE_EQ(p.target(refined, 1.0), 19.0);
}

TEST(IntervalAssignment, RejectsBadInput) {
  IntervalProblem p;
  p.add_curve(1, "Edge1");
  IntervalOptions o;
  o.size = 0;
  EXPECT_THROW(assign_intervals(p, o), std::invalid_argument);
  o = IntervalOptions{};
  p.equal.push_back({{0}, {3}, "bad"});
  EXPECT_THROW(assign_intervals(p, o), std::invalid_argument);
  IntervalProblem q;
  q.add_curve(-1, "Edge1");
  EXPECT_THROW(assign_intervals(q, o), std::invalid_argument);
}

}  // namespace
}  // namespace vorohex::mesh
