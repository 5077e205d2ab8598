// The registry of single-solid schemes the pipeline tries in order (SMESH's algorithm
// contract): each says whether it applies and why not, predicts its hex count, and meshes.
// A scheme may keep what applicable() found for evaluate() and compute() of the same solid.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "core/size_field.h"
#include "grid/composites.h"
#include "occ/solid.h"

namespace vorohex::pipeline::detail {

struct SchemeCheck {
  bool ok = false;
  std::string reason;  // why not (a sentence fragment naming entities)
};

struct SchemeEstimate {
  std::size_t hexes = 0;
  std::array<int, 3> intervals{};  // as MeshStats::intervals
};

struct SchemeMesh {
  bool ok = false;
  core::HexMesh mesh;
  std::array<int, 3> intervals{};
  std::vector<core::Diagnostic> diagnostics;  // the scheme's own (errors when !ok)
  core::Diagnostic summary;                   // an info saying what was done, when ok
  grid::SmallFeatures absorbed;               // the grid scheme's composites (empty otherwise)
};

class Scheme {
 public:
  virtual ~Scheme() = default;
  virtual const char* name() const = 0;
  // The reason, when not applicable, starts like "Not a block: ...".
  virtual SchemeCheck applicable(const occ::Solid& solid) = 0;
  // size: the global size and local sizes (a scheme that cannot grade uses the global).
  virtual SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) = 0;
  virtual SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                             const core::Progress& progress) = 0;
  // Whether its mesh follows local sizes (else it meshes at the global size).
  virtual bool grades() const { return true; }
};

// Every scheme name: map, sweep, multisweep, revolve, midpoint (the default order), and
// grid (the fallback, tried as a scheme only when named).
const std::vector<std::string>& scheme_names();

// The schemes for `names` (each one of scheme_names(); throws std::invalid_argument naming
// an unknown one).
std::vector<std::unique_ptr<Scheme>> make_schemes(const std::vector<std::string>& names);

}  // namespace vorohex::pipeline::detail
