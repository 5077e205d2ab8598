#include "voronoi/graph_io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "occ/primitives.h"

namespace vorohex::voronoi {
namespace {

TEST(VoronoiGraphIo, JsonNamesGovernorsAsFreeCadAndMarksFs) {
  const VoronoiResult r = compute_voronoi_graph(occ::make_box(3, 2, 1));
  ASSERT_TRUE(r.ok());
  const nlohmann::json j = nlohmann::json::parse(voronoi_graph_json(r));
  ASSERT_EQ(j["elements"].size(), r.graph.elements.size());
  int fs = 0;
  for (const auto& e : j["elements"]) {
    for (const auto& g : e["governors"]) {
      const std::string name = g.get<std::string>();
      EXPECT_TRUE(name.rfind("Face", 0) == 0 || name.rfind("Edge", 0) == 0 ||
                  name.rfind("Vertex", 0) == 0)
          << name;
    }
    if (e["kind"] == "face") fs += e["f_s"].get<bool>();
    if (e["kind"] == "edge") EXPECT_GE(e["polyline"].size(), 2u);
  }
  EXPECT_EQ(fs, 1);
  EXPECT_EQ(j["counts"]["f_s"], 1);
  EXPECT_GT(j["stats"]["cells"].get<long long>(), 0);
  EXPECT_EQ(j["status"], "ok");
}

TEST(VoronoiGraphIo, VtpHasOneCellPerElement) {
  const VoronoiResult r = compute_voronoi_graph(occ::make_box(1, 1, 1));
  ASSERT_TRUE(r.ok());
  const std::string json = ::testing::TempDir() + "/vorohex_graph.json";
  const std::string vtp = ::testing::TempDir() + "/vorohex_graph.vtp";
  std::string error;
  ASSERT_TRUE(write_voronoi_graph(r, json, vtp, &error)) << error;
  std::ifstream f(vtp);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  const size_t edges = r.graph.of_kind(ElementKind::edge).size();
  const size_t others = r.graph.elements.size() - edges;
  EXPECT_NE(text.find("NumberOfVerts=\"" + std::to_string(others) + "\""), std::string::npos);
  EXPECT_NE(text.find("NumberOfLines=\"" + std::to_string(edges) + "\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"governors\""), std::string::npos);
  EXPECT_FALSE(write_voronoi_graph(r, "/nonexistent-dir/x.json", "", &error));
  EXPECT_NE(error.find("cannot write"), std::string::npos);
  std::remove(json.c_str());
  std::remove(vtp.c_str());
}

}  // namespace
}  // namespace vorohex::voronoi
