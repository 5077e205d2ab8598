// Voronoi graph benchmark: seconds, octree cells and peak memory for the test fixtures and
// every model in a folder (default ../shared/models/hexme), with default options.
// Each solid runs in a forked child so that its peak resident memory is its own.
//
//   cmake --build build --target voronoi_bench
//   build/voronoi_bench [MODELS_DIR] > bench/results/voronoi.md
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "voronoi/voronoi_graph.h"

namespace {

using namespace vorohex;

struct Row {
  int faces = 0;
  long long cells = 0;
  double seconds = 0, model_seconds = 0;
  int vertices = 0, edges = 0, faces_v = 0, fs = 0, unverified = 0;
  int status = -1;  // 0 ok, 1 partial, 2 failed, -1 could not read
};

Row measure(const std::function<occ::Solid()>& make) {
  Row row;
  try {
    const occ::Solid solid = make();
    row.faces = solid.num_faces();
    const voronoi::VoronoiResult r = voronoi::compute_voronoi_graph(solid);
    row.cells = r.stats.cells;
    row.seconds = r.stats.seconds;
    row.model_seconds = r.stats.model_seconds;
    row.status = int(r.status);
    for (const auto& el : r.graph.elements) {
      row.vertices += el.kind == voronoi::ElementKind::vertex;
      row.edges += el.kind == voronoi::ElementKind::edge;
      row.faces_v += el.kind == voronoi::ElementKind::face;
      row.fs += el.fs;
      row.unverified += el.kind != voronoi::ElementKind::face && !el.verified;
    }
  } catch (const std::exception&) {
    row.status = -1;
  }
  return row;
}

// Runs `make` in a child; returns false on crash or timeout.
bool run_child(const std::function<occ::Solid()>& make, Row* row, long* peak_kb) {
  int fd[2];
  if (pipe(fd) != 0) return false;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    alarm(300);
    const Row r = measure(make);
    if (write(fd[1], &r, sizeof r) != sizeof r) _exit(2);
    _exit(0);
  }
  close(fd[1]);
  const ssize_t got = read(fd[0], row, sizeof *row);
  close(fd[0]);
  int status = 0;
  struct rusage usage {};
  wait4(pid, &status, 0, &usage);
  *peak_kb = usage.ru_maxrss;
  return got == sizeof *row && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "../shared/models/hexme";
  std::vector<std::pair<std::string, std::function<occ::Solid()>>> cases = {
      {"box 3x2x1", [] { return occ::make_box(3, 2, 1); }},
      {"cube", [] { return occ::make_box(1, 1, 1); }},
      {"triangular prism",
       [] {
         return occ::make_prism({{0, 0}, {1, 0}, {0.5, 0.8}}, 10);
       }},
      {"L-shape",
       [] {
         return occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}, 3);
       }},
      {"cylinder", [] { return occ::make_cylinder(1, 1); }},
      {"tapered brick", [] { return occ::make_tapered_brick(4, 3, 1, 0.3); }},
      {"plate with hole",
       [] {
         return occ::make_prism({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, 0.5,
                                {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
       }},
  };
  std::vector<std::string> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".step" || ext == ".stp" || ext == ".brep") files.push_back(e.path().string());
    }
  std::sort(files.begin(), files.end());
  for (const std::string& f : files)
    cases.push_back({std::filesystem::path(f).stem().string(), [f] {
                       occ::ReadResult r = occ::read_solid(f);
                       if (!r.ok()) throw std::runtime_error("unreadable");
                       return std::move(*r.solid);
                     }});

  std::printf(
      "| solid | faces | seconds | of which model | octree cells | peak MB | "
      "V vertices | V edges | V faces | f_s | unverified | status |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  const char* names[] = {"ok", "partial", "failed"};
  int within = 0, small = 0;
  for (const auto& [name, make] : cases) {
    Row row;
    long peak = 0;
    const bool ok = run_child(make, &row, &peak);
    if (!ok || row.status < 0) {
      std::printf("| %s | %d | - | - | - | %.0f | - | - | - | - | - | %s |\n", name.c_str(),
                  row.faces, peak / 1024.0, ok ? "not a single solid" : "crashed or timed out");
      std::fflush(stdout);
      continue;
    }
    if (row.faces <= 100) {
      ++small;
      within += row.seconds < 2.0 && peak / 1024.0 < 500;
    }
    std::printf("| %s | %d | %.3f | %.3f | %lld | %.0f | %d | %d | %d | %d | %d | %s |\n",
                name.c_str(), row.faces, row.seconds, row.model_seconds, row.cells, peak / 1024.0,
                row.vertices, row.edges, row.faces_v, row.fs, row.unverified, names[row.status]);
    std::fflush(stdout);
  }
  std::printf("\n%d of %d solids with at most 100 faces within 2 s and 500 MB.\n", within, small);
  return 0;
}
