// What the meshers ask of a size: the count an edge should get and where its nodes go. With
// no local sizes (field null or uniform) this is length / size and equal arc lengths, as
// before; with local sizes, the integral of ds / h along the edge and equal shares of it.
#pragma once

#include <vector>

#include "core/mesh_domain.h"
#include "core/size_field.h"

namespace vorohex::mesh::detail {

bool graded(const core::SizeField* field);

// The (real-valued) number of segments the edge should have.
double edge_segments(const core::MeshDomain& s, core::EdgeId e, double size,
                     const core::SizeField* field);

// n+1 points on the edge, first to last vertex, n segments of equal length or (graded)
// equal shares of the integral of ds / h.
std::vector<core::Vec3> edge_points(const core::MeshDomain& s, core::EdgeId e, int n,
                                    const core::SizeField* field);
// The same, unless `given` holds n + 1 nodes for e (per edge id, first to last vertex: the
// nodes a neighbouring sub-volume placed on the edge they share); then those.
std::vector<core::Vec3> edge_points(const core::MeshDomain& s, core::EdgeId e, int n,
                                    const core::SizeField* field,
                                    const std::vector<std::vector<core::Vec3>>& given);

// The same along a polyline (a straight segment, a sweep's linking path): n+1 points at equal
// shares of ds / h, interpolated on the polyline (end points kept).
std::vector<core::Vec3> graded_points(const std::vector<core::Vec3>& polyline, int n,
                                      const core::SizeField& field);

// Parameters in [0, 1] (first 0, last 1) of n+1 points along a straight segment a -> b:
// uniform, or graded by the field.
std::vector<double> graded_parameters(const core::Vec3& a, const core::Vec3& b, int n,
                                      const core::SizeField* field);

// The size at p: the field's, or `size`.
double size_at(const core::Vec3& p, double size, const core::SizeField* field);

}  // namespace vorohex::mesh::detail
