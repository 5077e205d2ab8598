#include "pipeline/detail/schemes.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "grid/grid_mesh.h"
#include "mesh/map_block.h"
#include "mesh/midpoint.h"
#include "mesh/multisweep.h"
#include "mesh/revolve.h"
#include "mesh/sweep.h"
#include "smooth/smooth_mesh.h"

namespace vorohex::pipeline::detail {
namespace {

class MapScheme : public Scheme {
 public:
  const char* name() const override { return "map"; }
  SchemeCheck applicable(const occ::Solid& solid) override {
    const mesh::Applicability a = mesh::map_block_applicable(solid);
    return {a.ok, "Not a block: " + a.reason};
  }
  SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) override {
    mesh::MapBlockOptions o;
    o.size = size.global();
    o.size_field = &size;
    const mesh::MapBlockEstimate e = mesh::map_block_evaluate(solid, o);
    return {e.hexes, e.intervals};
  }
  SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                     const core::Progress& progress) override {
    mesh::MapBlockOptions o;
    o.size = size.global();
    o.size_field = &size;
    mesh::MapBlockResult r = mesh::map_block(solid, o, progress);
    SchemeMesh m;
    m.ok = r.ok;
    m.mesh = std::move(r.mesh);
    m.intervals = r.intervals;
    m.diagnostics = std::move(r.diagnostics);
    return m;
  }
};

class SweepScheme : public Scheme {
 public:
  const char* name() const override { return "sweep"; }
  SchemeCheck applicable(const occ::Solid& solid) override {
    const mesh::SweepApplicability a = mesh::sweep_applicable(solid);
    return {a.ok, "Not a sweep: " + a.reason};
  }
  SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) override {
    mesh::SweepOptions o;
    o.size = size.global();
    o.size_field = &size;
    const mesh::SweepEstimate e = mesh::sweep_evaluate(solid, o);
    return {e.hexes, {0, 0, e.layers}};
  }
  SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                     const core::Progress& progress) override {
    mesh::SweepOptions o;
    o.size = size.global();
    o.size_field = &size;
    mesh::SweepResult r = mesh::sweep(solid, o, progress);
    // Layers that fold swept one way may not the other: a source with a sliver of a quad
    // (HexMe n04: a triangle with 15-degree corners, swept to one with 50-degree corners)
    // folds where the other end's mesh, carried across, does not.
    if (!r.ok && r.folded > 0 && !progress.cancelled()) {
      mesh::SweepOptions back = o;
      back.avoid_sources = {r.source.value()};
      mesh::SweepResult other = mesh::sweep(solid, back, progress);
      if (other.source != r.source && (other.ok || (other.folded > 0 && other.folded < r.folded)))
        r = std::move(other);
    }
    if (!r.ok && r.folded > 0 && !progress.cancelled()) {  // the target's nodes along the axis
      mesh::SweepOptions along = o;
      along.target_along_axis = true;
      mesh::SweepResult other = mesh::sweep(solid, along, progress);
      if (other.ok || (other.folded > 0 && other.folded < r.folded)) r = std::move(other);
    }
    if (!r.ok && r.folded > 0 && !progress.cancelled()) {  // each layer within its boundary
      mesh::SweepOptions smoothed = o;
      smoothed.smooth_layers = true;
      mesh::SweepResult other = mesh::sweep(solid, smoothed, progress);
      if (other.ok || (other.folded > 0 && other.folded < r.folded)) r = std::move(other);
    }
    if (!r.ok && r.folded > 0 && !progress.cancelled() &&
        smooth::untangle_folded(r.mesh, solid, {}, &size, progress))
      mesh::accept_untangled(r);
    SchemeMesh m;
    m.ok = r.ok;
    m.intervals = {0, 0, r.layers};
    m.diagnostics = std::move(r.diagnostics);
    if (r.ok) {
      m.mesh = std::move(r.mesh);
      m.summary = core::make_info("sweep",
                                  "Swept from " + core::entity_name(r.source) + " to " +
                                      core::entity_name(r.target) + " in " +
                                      std::to_string(r.layers) + " layers.",
                                  {core::entity_name(r.source), core::entity_name(r.target)});
    }
    return m;
  }
};

class MultisweepScheme : public Scheme {
 public:
  const char* name() const override { return "multisweep"; }
  SchemeCheck applicable(const occ::Solid& solid) override {
    const mesh::MultisweepApplicability a = mesh::multisweep_applicable(solid);
    return {a.ok, "Not prismatic (multisweep): " + a.reason};
  }
  SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) override {
    mesh::MultisweepOptions o;
    o.size = size.global();
    o.size_field = &size;
    const mesh::MultisweepEstimate e = mesh::multisweep_evaluate(solid, o);
    return {e.hexes, {0, 0, e.layers}};
  }
  SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                     const core::Progress& progress) override {
    mesh::MultisweepOptions o;
    o.size = size.global();
    o.size_field = &size;
    mesh::MultisweepResult r = mesh::multisweep(solid, o, progress);
    SchemeMesh m;
    m.ok = r.ok;
    m.intervals = {0, 0, r.layers};
    m.diagnostics = std::move(r.diagnostics);
    if (r.ok) {
      m.mesh = std::move(r.mesh);
      std::ostringstream s;
      const core::Vec3 a = r.axis + core::Vec3::Zero();  // + 0: no "-0" in the text
      s << "Swept along (" << a.x() << ", " << a.y() << ", " << a.z() << ") through "
        << r.levels - 1 << (r.levels == 2 ? " slab" : " slabs") << " in " << r.layers
        << " layers: the caps' outlines overlaid into " << r.regions
        << " regions meshed with quads (min 2-D quality " << std::setprecision(3)
        << r.region_min_quality << "), extruded slab by slab.";
      m.summary = core::make_info("multisweep", s.str());
    }
    return m;
  }
};

class RevolveScheme : public Scheme {
 public:
  const char* name() const override { return "revolve"; }
  SchemeCheck applicable(const occ::Solid& solid) override {
    const mesh::RevolveApplicability a = mesh::revolve_applicable(solid);
    return {a.ok, "Not of revolution: " + a.reason};
  }
  SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) override {
    mesh::RevolveOptions o;
    o.size = size.global();
    o.size_field = &size;
    const mesh::RevolveEstimate e = mesh::revolve_evaluate(solid, o);
    return {e.hexes, {0, 0, e.sectors}};
  }
  SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                     const core::Progress& progress) override {
    mesh::RevolveOptions o;
    o.size = size.global();
    o.size_field = &size;
    mesh::RevolveResult r = mesh::revolve(solid, o, progress);
    SchemeMesh m;
    m.ok = r.ok;
    m.intervals = {0, 0, r.sectors};
    m.diagnostics = std::move(r.diagnostics);
    if (r.ok) {
      m.mesh = std::move(r.mesh);
      std::ostringstream s;
      s << "Revolved about the axis through (" << r.origin.x() << ", " << r.origin.y() << ", "
        << r.origin.z() << ") along (" << r.axis.x() << ", " << r.axis.y() << ", " << r.axis.z()
        << ") in " << r.sectors << " sectors: its meridian section meshed with quads (min 2-D "
        << "quality " << std::setprecision(3) << r.section_min_quality << ")";
      if (r.cores > 0)
        s << ", with " << r.cores << (r.cores == 1 ? " core" : " cores") << " of radius "
          << r.core_radius << " swept along the axis from an O-grid disc";
      s << ".";
      m.summary = core::make_info("revolve", s.str());
    }
    return m;
  }
};

class MidpointScheme : public Scheme {
 public:
  const char* name() const override { return "midpoint"; }
  bool grades() const override { return false; }  // one subdivision count for all
  SchemeCheck applicable(const occ::Solid& solid) override {
    const mesh::Applicability a = mesh::midpoint_applicable(solid);
    return {a.ok, "No midpoint subdivision: " + a.reason};
  }
  SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) override {
    mesh::MidpointOptions o;
    o.size = size.global();
    const mesh::MidpointEstimate e = mesh::midpoint_evaluate(solid, o);
    return {e.hexes, {e.subdivisions, e.subdivisions, e.subdivisions}};
  }
  SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                     const core::Progress& progress) override {
    mesh::MidpointOptions o;
    o.size = size.global();
    mesh::MidpointResult r = mesh::midpoint_subdivide(solid, o, progress);
    SchemeMesh m;
    m.ok = r.ok;
    m.intervals = {r.subdivisions, r.subdivisions, r.subdivisions};
    m.diagnostics = std::move(r.diagnostics);
    if (r.ok) {
      m.mesh = std::move(r.mesh);
      m.summary = core::make_info(
          "midpoint", std::string("Midpoint subdivision of a convex polyhedron (") + r.variant +
                          "), refined " + std::to_string(r.subdivisions) + " times per direction.");
    }
    return m;
  }
};

// The grid mesher for any closed solid (the pipeline's fallback; as a scheme only when
// asked for by name). Its optimisation is the global smoothing every result goes through.
class GridScheme : public Scheme {
 public:
  const char* name() const override { return "grid"; }
  bool grades() const override { return false; }  // a uniform grid (no octree yet)
  SchemeCheck applicable(const occ::Solid&) override { return {true, ""}; }
  SchemeEstimate evaluate(const occ::Solid& solid, const core::SizeField& size) override {
    // Core cells and one pillow hex per boundary quad.
    double area = 0;
    for (core::FaceId f : solid.faces()) area += std::abs(solid.area(f));
    const double h = size.global(), h3 = h * h * h;
    return {std::size_t(std::abs(solid.volume()) / h3 + area / (h * h)), {0, 0, 0}};
  }
  SchemeMesh compute(const occ::Solid& solid, const core::SizeField& size,
                     const core::Progress& progress) override {
    grid::GridOptions o;
    o.size = size.global();
    o.laplacian_iterations = 0;
    o.optimisation_passes = 0;
    grid::GridResult r = grid::grid_mesh(solid, o, progress);
    SchemeMesh m;
    m.ok = r.ok;
    for (core::Diagnostic& d : r.diagnostics)
      if (d.code == "grid" && r.ok)
        m.summary = std::move(d);
      else
        m.diagnostics.push_back(std::move(d));
    if (r.ok) m.mesh = std::move(r.mesh), m.absorbed = std::move(r.absorbed);
    return m;
  }
};

}  // namespace

const std::vector<std::string>& scheme_names() {
  static const std::vector<std::string> names = {"map",     "sweep",    "multisweep",
                                                 "revolve", "midpoint", "grid"};
  return names;
}

std::vector<std::unique_ptr<Scheme>> make_schemes(const std::vector<std::string>& names) {
  std::vector<std::unique_ptr<Scheme>> out;
  for (const std::string& n : names) {
    if (n == "map")
      out.push_back(std::make_unique<MapScheme>());
    else if (n == "sweep")
      out.push_back(std::make_unique<SweepScheme>());
    else if (n == "multisweep")
      out.push_back(std::make_unique<MultisweepScheme>());
    else if (n == "revolve")
      out.push_back(std::make_unique<RevolveScheme>());
    else if (n == "midpoint")
      out.push_back(std::make_unique<MidpointScheme>());
    else if (n == "grid")
      out.push_back(std::make_unique<GridScheme>());
    else {
      std::string known;
      for (const std::string& k : scheme_names()) known += (known.empty() ? "" : ", ") + k;
      throw std::invalid_argument("unknown scheme '" + n + "' (known: " + known + ")");
    }
  }
  return out;
}

}  // namespace vorohex::pipeline::detail
