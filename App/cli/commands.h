// The `vorohex` sub-commands. Each returns the process exit code:
// 0 success (valid mesh), 1 meshing failed or the mesh is invalid, 2 bad input or usage.
#pragma once

#include <string>
#include <vector>

#include "core/progress.h"

namespace vorohex::cli {

constexpr int kExitOk = 0;
constexpr int kExitInvalid = 1;
constexpr int kExitBadInput = 2;

int run_mesh(const std::vector<std::string>& args);
int run_check(const std::vector<std::string>& args);
int run_voronoi(const std::vector<std::string>& args);
int run_decompose(const std::vector<std::string>& args);

// Progress lines on stderr ("[   1.25s] split     50%"): one per stage and every 25 %
// within it; none when quiet.
core::Progress progress_printer(bool quiet);

extern const char* const kMeshUsage;
extern const char* const kCheckUsage;
extern const char* const kVoronoiUsage;
extern const char* const kDecomposeUsage;

}  // namespace vorohex::cli
