// Local size control (issue 21): a target edge length that is smaller near chosen faces,
// edges and vertices and grows smoothly into the global size away from them:
//
//   h(p) = min(global, min over sources i of (size_i + grading * distance(p, entity_i)))
//
// (Gmsh's Distance + Threshold fields give the same shape.) Distances are exact projections
// on the solid the sources name; a source's bounding box culls points it cannot reach. Every
// mesher asks the field for its counts (the integral of ds / h along a curve) and its node
// placement (equal shares of that integral), so interval assignment, submapping and sweeps
// all follow it. The field works in model coordinates, so the sub-volumes of a
// decomposition, which have their own entity ids, use the field of the whole solid.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/geometry.h"
#include "core/mesh_domain.h"

namespace vorohex::core {

// One local size as a user writes it: an entity name ("Face7", "Edge3", "Vertex2"; FreeCAD's
// sub-element names) and a size in model units.
struct LocalSize {
  std::string entity;
  double size = 0;
};

class SizeField {
 public:
  // A uniform field (no sources).
  explicit SizeField(double global_size = 1.0);
  // Throws std::invalid_argument naming the entry: an unknown or malformed entity name,
  // an entity the solid does not have, a size that is not finite and > 0, a global size or
  // grading that is not finite and > 0. An entity named twice keeps the smaller size.
  // `domain` must outlive the field.
  SizeField(const MeshDomain& domain, double global_size, const std::vector<LocalSize>& sizes,
            double grading);

  double global() const { return global_; }
  bool uniform() const { return sources_.empty(); }
  double min_size() const;  // the smallest size anywhere (the global size when uniform)
  double at(const Vec3& p) const;

  // The field seen from a plane that a prismatic solid is swept along `axis` from: at p, the
  // smallest size at p moved to each of the given heights ((q - origin) . axis = height).
  // A 2-D mesh of the cross-section then refines wherever any slab asks for it.
  SizeField extruded(const Vec3& origin, const Vec3& axis, std::vector<double> heights) const;
  // The same for a solid of revolution meshed from one meridian section: at p, the smallest
  // size at p turned about the axis by `turns` equal angles.
  SizeField revolved(const Vec3& origin, const Vec3& axis, int turns) const;

  // The field times `factor` everywhere (its global and local sizes and its grading): a
  // mesh made again finer where it failed at the sizes asked for.
  SizeField scaled(double factor) const;

  // The number of segments of size h that fit along a polyline: the integral of ds / h(s)
  // (length / global when uniform).
  double segments_along(const std::vector<Vec3>& polyline) const;
  // Cumulative integral of ds / h at each polyline point (first 0, last segments_along).
  std::vector<double> cumulative(const std::vector<Vec3>& polyline) const;

  // Warnings found while building (a local size not below the global size has no effect).
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  // The sources as applied (each entity once, only sizes below the global one), for
  // reports: "Face7" -> size.
  const std::vector<LocalSize>& applied() const { return applied_; }

  // About how many hexahedra the graded layers around the sources add to volume / size^3:
  // the integral of 1 / h^3 - 1 / size^3 over the distance d from each entity, on the
  // solid's side of a face (its area), around an edge (a half cylinder, pi d per unit
  // length) and a vertex (a quarter ball, pi d^2 / 2; corners of solids hold an eighth to
  // a half), in closed form. A structured mesh has about this many more, or more (its layers and
  // sectors run through); used to refuse tiny local sizes before meshing.
  double graded_cells() const;

 private:
  struct Source {
    enum Kind { vertex, edge, face } kind;
    int id;
    double size;
    BoundingBox box;
  };
  double distance(const Source& s, const Vec3& p) const;
  double at_point(const Vec3& p) const;

  const MeshDomain* domain_ = nullptr;
  double global_ = 1.0;
  double grading_ = 0.3;
  std::vector<Source> sources_;
  // extruded() / revolved(): at(p) is the minimum over these images of p.
  std::vector<std::function<Vec3(const Vec3&)>> views_;
  std::vector<LocalSize> applied_;
  std::vector<Diagnostic> diagnostics_;
};

// Parses "Face7" / "Edge3" / "Vertex2" into its kind and 1-based id; false when malformed.
bool parse_entity_name(const std::string& name, char& kind, int& id);

}  // namespace vorohex::core
