// _VoroHexCore: the pybind11 binding of the C++ pipeline (the only C++ that knows Python).
// It deals in plain values (BREP strings, flat byte buffers, option structs); VoroHex.py
// next to it adds the FreeCAD side (Part.Shape, Fem.FemMesh, numpy) without which this
// module stays testable from any Python.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/isolated_call.h"
#include "core/progress.h"
#include "decompose/decomposition_io.h"
#include "io/mesh_io.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"
#include "quality/scaled_jacobian.h"
#include "voronoi/graph_io.h"
#include "voronoi/voronoi_graph.h"

namespace py = pybind11;
using namespace vorohex;

namespace {

// A run stopped by its progress callback (VoroHex.Cancelled in Python).
struct CancelledError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Shared so a Python object keeps the solid alive while a mesh result refers to it.
using SolidPtr = std::shared_ptr<occ::Solid>;

struct CancelToken {
  std::atomic<bool> flag{false};
};

template <class T>
py::bytes to_bytes(const std::vector<T>& v) {
  return py::bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

py::bytes node_bytes(const core::HexMesh& m) {
  std::vector<double> flat;
  flat.reserve(3 * m.num_nodes());
  for (const auto& p : m.points()) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  return to_bytes(flat);
}

py::bytes hex_bytes(const core::HexMesh& m) {
  std::vector<std::int32_t> flat;
  flat.reserve(8 * m.num_hexes());
  for (const auto& h : m.hexes()) flat.insert(flat.end(), h.begin(), h.end());
  return to_bytes(flat);
}

// Builds a mesh from flat float64 xyz and int32 VTK-order connectivity buffers.
core::HexMesh mesh_from_bytes(const std::string& nodes, const std::string& hexes) {
  if (nodes.size() % (3 * sizeof(double)) != 0)
    throw std::invalid_argument("nodes buffer is not a multiple of 3 float64 values");
  if (hexes.size() % (8 * sizeof(std::int32_t)) != 0)
    throw std::invalid_argument("hexes buffer is not a multiple of 8 int32 values");
  const std::size_t n = nodes.size() / (3 * sizeof(double));
  const std::size_t m = hexes.size() / (8 * sizeof(std::int32_t));
  core::HexMesh mesh;
  mesh.reserve(n, m);
  for (std::size_t i = 0; i < n; ++i) {
    double xyz[3];
    std::memcpy(xyz, nodes.data() + i * sizeof(xyz), sizeof(xyz));
    mesh.add_node({xyz[0], xyz[1], xyz[2]});
  }
  for (std::size_t i = 0; i < m; ++i) {
    core::HexNodes h;
    std::memcpy(h.data(), hexes.data() + i * sizeof(h), sizeof(h));
    for (auto v : h)
      if (v < 0 || static_cast<std::size_t>(v) >= n)
        throw std::invalid_argument("hex " + std::to_string(i) + " refers to node " +
                                    std::to_string(v) + " but there are " + std::to_string(n) +
                                    " nodes");
    mesh.add_hex(h);
  }
  return mesh;
}

py::list diagnostics_list(const std::vector<core::Diagnostic>& ds) {
  py::list out;
  for (const auto& d : ds) out.append(py::cast(d));
  return out;
}

void bind_types(py::module_& m) {
  py::class_<core::Diagnostic>(m, "Diagnostic", "A message from a stage: severity, code, entities")
      .def_property_readonly(
          "severity", [](const core::Diagnostic& d) { return core::severity_name(d.severity); })
      .def_readonly("code", &core::Diagnostic::code)
      .def_readonly("message", &core::Diagnostic::message)
      .def_readonly("entities", &core::Diagnostic::entities)
      .def("__str__", [](const core::Diagnostic& d) { return core::format(d); })
      .def("__repr__",
           [](const core::Diagnostic& d) { return "<Diagnostic " + core::format(d) + ">"; });

  py::class_<quality::QualityStats>(m, "QualityStats")
      .def_readonly("count", &quality::QualityStats::count)
      .def_readonly("min", &quality::QualityStats::min)
      .def_readonly("max", &quality::QualityStats::max)
      .def_readonly("mean", &quality::QualityStats::mean)
      .def_property_readonly("histogram",
                             [](const quality::QualityStats& s) {
                               return std::vector<std::size_t>(s.histogram.begin(),
                                                               s.histogram.end());
                             })
      .def_readonly("fraction_below_0_2", &quality::QualityStats::fraction_below_0_2)
      .def_readonly("inverted", &quality::QualityStats::inverted);

  using R = quality::CheckReport;
  py::class_<R>(m, "CheckReport")
      .def_readonly("valid", &R::valid)
      .def_readonly("nodes", &R::nodes)
      .def_readonly("hexes", &R::hexes)
      .def_readonly("scaled_jacobian", &R::scaled_jacobian)
      .def_readonly("non_positive", &R::non_positive)
      .def_readonly("degenerate", &R::degenerate)
      .def_readonly("interior_quads", &R::interior_quads)
      .def_readonly("boundary_quads", &R::boundary_quads)
      .def_readonly("non_manifold_quads", &R::non_manifold_quads)
      .def_readonly("open_boundary_edges", &R::open_boundary_edges)
      .def_readonly("unused_nodes", &R::unused_nodes)
      .def_readonly("has_cad", &R::has_cad)
      .def_readonly("mesh_volume", &R::mesh_volume)
      .def_readonly("cad_volume", &R::cad_volume)
      .def_readonly("volume_rel_error", &R::volume_rel_error)
      .def_readonly("volume_allowance", &R::volume_allowance)
      .def_readonly("max_boundary_distance", &R::max_boundary_distance)
      .def_readonly("max_boundary_distance_rel", &R::max_boundary_distance_rel)
      .def_property_readonly("diagnostics",
                             [](const R& r) { return diagnostics_list(r.diagnostics); })
      .def_property_readonly(
          "worst",
          [](const R& r) {
            py::list out;
            for (const quality::WorstHex& w : r.worst) {
              py::dict d;
              d["hex"] = w.hex;
              d["scaled_jacobian"] = w.scaled_jacobian;
              d["centre"] = py::make_tuple(w.centre.x(), w.centre.y(), w.centre.z());
              d["entities"] = w.entities;
              out.append(d);
            }
            return out;
          },
          "The (at most) three hexahedra of lowest scaled Jacobian, worst first: dicts with "
          "hex (0-based index), scaled_jacobian, centre and entities (the CAD entities its "
          "nodes lie on: 'Vertex3', 'Edge9', 'Face2').");

  using S = pipeline::MeshStats;
  py::class_<S>(m, "MeshStats")
      .def_readonly("size_used", &S::size_used)
      .def_readonly("intervals", &S::intervals)
      .def_readonly("seconds_meshing", &S::seconds_meshing)
      .def_readonly("seconds_smoothing", &S::seconds_smoothing)
      .def_readonly("seconds_checking", &S::seconds_checking)
      .def_readonly("min_sj_before_smoothing", &S::min_sj_before_smoothing)
      .def_readonly("mean_sj_before_smoothing", &S::mean_sj_before_smoothing)
      .def_readonly("sub_volumes", &S::sub_volumes)
      .def_readonly("sub_volume_schemes", &S::sub_volume_schemes)
      .def_readonly("sub_volume_types", &S::sub_volume_types)
      .def_readonly("scheme", &S::scheme)
      .def_readonly("absorbed_deviation", &S::absorbed_deviation)
      .def_readonly("fallback_beside", &S::fallback_beside)
      .def_property_readonly("local_sizes", [](const S& st) {
        std::vector<std::pair<std::string, double>> out;
        for (const core::LocalSize& l : st.local_sizes) out.emplace_back(l.entity, l.size);
        return out;
      });

  // Flat option names: the one list VoroHex.py maps FreeCAD properties onto.
  using O = pipeline::MeshOptions;
  py::class_<O>(m, "MeshOptions")
      .def(py::init<>())
      .def_readwrite("size", &O::size, "target edge length, model units; 0 = diagonal / 20")
      .def_readwrite("max_hexes", &O::max_hexes, "refuse up front above this predicted count")
      .def_property(
          "local_sizes",
          [](const O& o) {
            std::vector<std::pair<std::string, double>> out;
            for (const core::LocalSize& l : o.local_sizes) out.emplace_back(l.entity, l.size);
            return out;
          },
          [](O& o, const std::vector<std::pair<std::string, double>>& v) {
            o.local_sizes.clear();
            for (const auto& [entity, size] : v) o.local_sizes.push_back({entity, size});
          },
          "smaller sizes at CAD entities: [(\"Face7\", 0.5), ...], graded into size")
      .def_readwrite("size_grading", &O::size_grading,
                     "growth of the size per unit distance from a local size, in (0, 10]")
      .def_readwrite("time_limit", &O::time_limit,
                     "seconds after which meshing stops like a cancel (0: none)")
      .def_readwrite("schemes", &O::schemes,
                     "single-solid schemes tried in this order (map, sweep, multisweep, "
                     "revolve, midpoint; grid only when named); one left out is never used")
      .def_readwrite("fallback", &O::fallback,
                     "where no structured scheme applies: the grid mesher (reported as a "
                     "warning); False refuses such solids")
      .def_readwrite("fallback_scheme", &O::fallback_scheme,
                     "the fallback: \"grid\" (core grid, pillow layer, features captured) or "
                     "\"tet-split\" (tetrahedra split into hexahedra, for comparison)")
      .def_readwrite("fallback_beside", &O::fallback_beside,
                     "on two cores or more, compute the fallback beside the decomposition "
                     "(a second child process; the same result, sooner); False: after it")
      .def_readwrite("decompose", &O::decompose,
                     "where no single scheme applies: cut along the Voronoi graph and mesh the "
                     "sub-volumes into one conforming mesh (before any fallback)")
      .def_readwrite("decomposition_time_limit", &O::decomposition_time_limit,
                     "seconds the graph and the cut may take (> 0), then the fallback")
      .def_readwrite("sharp_angle", &O::sharp_angle,
                     "decomposition: dihedral angle (degrees) below which a [1] edge is [1s]")
      .def_property(
          "eps", [](const O& o) { return o.graph.eps; }, [](O& o, double v) { o.graph.eps = v; },
          "Voronoi graph: merge tolerance and finest cell, x bounding-box diagonal")
      .def_property(
          "delta", [](const O& o) { return o.graph.delta; },
          [](O& o, double v) { o.graph.delta = v; },
          "Voronoi graph: embedding accuracy, x bounding-box diagonal")
      .def_property(
          "max_depth", [](const O& o) { return o.graph.max_depth; },
          [](O& o, int v) { o.graph.max_depth = v; }, "Voronoi graph: maximum octree depth, 1..12")
      .def_property(
          "smooth_iterations", [](const O& o) { return o.smoothing.laplacian_iterations; },
          [](O& o, int v) { o.smoothing.laplacian_iterations = v; },
          "smoothing: Laplacian sweeps (>= 0; 0 and smooth_passes 0 = no smoothing)")
      .def_property(
          "smooth_passes", [](const O& o) { return o.smoothing.optimisation_passes; },
          [](O& o, int v) { o.smoothing.optimisation_passes = v; },
          "smoothing: untangling and worst-element optimisation passes (>= 0)")
      .def_property(
          "smooth_quality_target", [](const O& o) { return o.smoothing.quality_target; },
          [](O& o, double v) { o.smoothing.quality_target = v; },
          "smoothing: hexes below this scaled Jacobian are optimised, in (0, 1]")
      .def_property(
          "smooth_relaxation", [](const O& o) { return o.smoothing.relaxation; },
          [](O& o, double v) { o.smoothing.relaxation = v; },
          "smoothing: fraction of the Laplacian step taken, in (0, 1]")
      .def_property(
          "smooth_tolerance", [](const O& o) { return o.smoothing.tolerance; },
          [](O& o, double v) { o.smoothing.tolerance = v; },
          "smoothing: convergence, node move relative to its mean edge length (>= 0)")
      .def_property(
          "volume_rel_tol", [](const O& o) { return o.check.volume_rel_tol; },
          [](O& o, double v) { o.check.volume_rel_tol = v; },
          "check: allowed relative volume error vs the CAD solid")
      .def_property(
          "distance_rel_tol", [](const O& o) { return o.check.distance_rel_tol; },
          [](O& o, double v) { o.check.distance_rel_tol = v; },
          "check: allowed boundary node distance, relative to the diagonal")
      .def_readwrite(
          "order", &O::order,
          "element order: 1 (8-node hexahedra) or 2 (20-node, mid-edge nodes on the CAD)")
      .def("validate", &O::validate, "raises ValueError naming the bad option");

  using V = voronoi::VoronoiOptions;
  py::class_<V>(m, "VoronoiOptions")
      .def(py::init<>())
      .def_readwrite("eps", &V::eps, "merge tolerance and finest cell, x bounding-box diagonal")
      .def_readwrite("delta", &V::delta, "embedding accuracy, x bounding-box diagonal")
      .def_readwrite("max_depth", &V::max_depth, "maximum octree depth, 1..12")
      .def_readwrite("linear_tolerance", &V::linear_tolerance,
                     "chord tolerance of curved entities, x bounding-box diagonal")
      .def(
          "validate",
          [](const V& o) {
            if (std::string why = o.validate(); !why.empty()) throw std::invalid_argument(why);
          },
          "raises ValueError naming the bad option");

  py::class_<CancelToken, std::shared_ptr<CancelToken>>(m, "CancelToken")
      .def(py::init<>())
      .def("cancel", [](CancelToken& t) { t.flag = true; })
      .def_property_readonly("cancelled", [](const CancelToken& t) { return t.flag.load(); });
}

void bind_mesh(py::module_& m) {
  py::class_<core::HexMesh, std::shared_ptr<core::HexMesh>>(m, "HexMesh",
                                                            "All-hex mesh, VTK node order")
      .def_static(
          "from_bytes",
          [](py::bytes nodes, py::bytes hexes) {
            return std::make_shared<core::HexMesh>(mesh_from_bytes(nodes, hexes));
          },
          py::arg("nodes"), py::arg("hexes"),
          "from float64 xyz and int32 connectivity (VTK order) buffers")
      .def_property_readonly("num_nodes", &core::HexMesh::num_nodes)
      .def_property_readonly("num_hexes", &core::HexMesh::num_hexes)
      .def("node_bytes", &node_bytes, "float64 x y z per node")
      .def("hex_bytes", &hex_bytes, "int32 8 node indices per hex, VTK order")
      .def_property_readonly("order", &core::HexMesh::order, "1 (8-node) or 2 (20-node hexahedra)")
      .def(
          "mid_edge_bytes",
          [](const core::HexMesh& h) {
            std::vector<std::int32_t> flat;
            flat.reserve(12 * h.mid_edge_nodes().size());
            for (const auto& m : h.mid_edge_nodes()) flat.insert(flat.end(), m.begin(), m.end());
            return to_bytes(flat);
          },
          "int32 12 mid-edge node indices per hex (VTK_QUADRATIC_HEXAHEDRON order); empty for "
          "a first-order mesh")
      .def("sub_volume_bytes", [](const core::HexMesh& h) { return to_bytes(h.sub_volumes()); })
      .def(
          "node_class_bytes",
          [](const core::HexMesh& h) {
            std::vector<std::int32_t> flat;
            for (const auto& c : h.node_classes()) flat.insert(flat.end(), {c.dim, c.id});
            return to_bytes(flat);
          },
          "int32 (dimension, entity id) per node")
      .def("scaled_jacobians", &quality::scaled_jacobians)
      .def(
          "hex_volumes",
          [](const core::HexMesh& h) {
            std::vector<double> v;
            v.reserve(h.num_hexes());
            for (std::size_t i = 0; i < h.num_hexes(); ++i)
              v.push_back(quality::hex_volume(h.corners(core::HexId(static_cast<int>(i)))));
            return v;
          },
          "signed trilinear volume per hex");

  py::class_<occ::Solid, SolidPtr>(m, "Solid", "A CAD solid read by OCCT")
      .def_property_readonly("num_faces", &occ::Solid::num_faces)
      .def_property_readonly("num_edges", &occ::Solid::num_edges)
      .def_property_readonly("num_vertices", &occ::Solid::num_vertices)
      .def_property_readonly("volume", &occ::Solid::volume)
      .def_property_readonly("diagonal", &occ::Solid::diagonal);

  py::class_<pipeline::MeshResult, std::shared_ptr<pipeline::MeshResult>>(m, "MeshResult")
      .def_readonly("ok", &pipeline::MeshResult::ok)
      .def_property_readonly("mesh",
                             [](std::shared_ptr<pipeline::MeshResult> r) {
                               // aliasing pointer: the mesh lives as long as the result
                               return std::shared_ptr<core::HexMesh>(r, &r->mesh);
                             })
      .def_readonly("check", &pipeline::MeshResult::check)
      .def_readonly("scaled_jacobian", &pipeline::MeshResult::scaled_jacobian)
      .def_readonly("stats", &pipeline::MeshResult::stats)
      .def_property_readonly(
          "diagnostics",
          [](const pipeline::MeshResult& r) { return diagnostics_list(r.diagnostics); })
      .def_property_readonly(
          "groups",
          [](const pipeline::MeshResult& r) {
            py::list out;
            for (const io::NamedGroup& g : r.groups) {
              py::dict d;
              d["name"] = g.name;
              d["dim"] = g.dim;
              d["id"] = g.id;
              d["nodes"] = to_bytes(g.nodes);  // int32, 0-based
              std::vector<std::int32_t> faces;
              for (const io::GroupFace& f : g.faces) faces.insert(faces.end(), {f.hex, f.face});
              d["faces"] = to_bytes(faces);  // int32 (hex, kHexFaces index) pairs
              d["mesh_edges"] = g.edges.size();
              out.append(d);
            }
            return out;
          },
          "named groups per CAD face, edge, vertex: dicts with name, dim, id, nodes (int32 "
          "bytes, 0-based), faces (int32 bytes: hex, local face pairs), mesh_edges");
}

// Reads a BREP string into one solid (or several glued); returns (solid or None, diagnostics).
py::tuple read_brep(const std::string& brep, bool several_solids) {
  occ::ReadResult r;
  {
    py::gil_scoped_release nogil;
    occ::ReadOptions options;
    options.several_solids = several_solids;
    r = occ::read_solid_from_brep_string(brep, options);
  }
  SolidPtr solid(r.solid.release());
  return py::make_tuple(solid ? py::cast(solid) : py::none(), diagnostics_list(r.diagnostics));
}

std::shared_ptr<pipeline::MeshResult> generate(SolidPtr solid, const pipeline::MeshOptions& options,
                                               py::object progress,
                                               std::shared_ptr<CancelToken> cancel) {
  if (!solid) throw std::invalid_argument("no solid given");
  options.validate();
  if (!cancel) cancel = std::make_shared<CancelToken>();
  // The callback runs on the meshing thread with the GIL released: take it back, and turn a
  // Python exception (or a False return) into cancellation so the pipeline stops early.
  std::unique_ptr<py::error_already_set> callback_error;
  core::Progress::Callback cb;
  if (!progress.is_none()) {
    cb = [&](std::string_view stage, double fraction) {
      py::gil_scoped_acquire gil;
      if (callback_error) return;
      try {
        py::object ret = progress(std::string(stage), fraction);
        if (!ret.is_none() && !ret.cast<bool>()) cancel->flag = true;
      } catch (py::error_already_set& e) {
        callback_error = std::make_unique<py::error_already_set>(std::move(e));
        cancel->flag = true;
      }
    };
  }
  auto result = std::make_shared<pipeline::MeshResult>();
  {
    py::gil_scoped_release nogil;
    *result = pipeline::generate_mesh(*solid, options, core::Progress(cb, &cancel->flag));
  }
  if (callback_error) throw std::move(*callback_error);
  return result;
}

// The embedded Voronoi graph as JSON text (graph_io.h layout); VoroHex.py parses it.
std::string voronoi_json(SolidPtr solid, const voronoi::VoronoiOptions& options) {
  if (!solid) throw std::invalid_argument("no solid given");
  if (std::string why = options.validate(); !why.empty()) throw std::invalid_argument(why);
  py::gil_scoped_release nogil;
  return voronoi::voronoi_graph_json(voronoi::compute_voronoi_graph(*solid, options));
}

// Runs `work` in a child process (core/isolated_call.h) with the GIL released: the caller
// gets the child's reports (`work` gets a Progress whose reports cross, core::IsolatedJob),
// or before any heartbeats, through `progress(stage, fraction)` (False cancels: the child
// is killed, the Python exception Cancelled is raised), and a crash inside the child is an
// error, not the end of FreeCAD. With `kill_after` > 0 the child is also killed after that
// many seconds, and TimeLimitError is thrown.
struct TimeLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
std::string run_isolated(const std::function<std::string(const core::Progress&)>& work,
                         py::object progress, const char* stage, double kill_after = 0) {
  std::atomic<bool> cancel{false};
  std::unique_ptr<py::error_already_set> callback_error;
  core::Progress::Callback cb;
  if (!progress.is_none())
    cb = [&](std::string_view s, double fraction) {
      py::gil_scoped_acquire gil;
      if (callback_error) return;
      try {
        py::object ret = progress(std::string(s), fraction);
        if (!ret.is_none() && !ret.cast<bool>()) cancel = true;
      } catch (py::error_already_set& e) {
        callback_error = std::make_unique<py::error_already_set>(std::move(e));
        cancel = true;
      }
    };
  core::IsolatedResult run;
  {
    py::gil_scoped_release nogil;
    core::IsolatedCallOptions o;
    o.stage = stage;
    const core::Progress p(cb, &cancel);
    const core::Progress limited = kill_after > 0 ? p.with_time_limit(kill_after) : p;
    core::IsolatedJob job(work, limited);
    run = job.take(limited, o);
  }
  if (callback_error) throw std::move(*callback_error);
  switch (run.status) {
    case core::IsolatedResult::Status::ok:
      return run.data;
    case core::IsolatedResult::Status::cancelled:
      if (!cancel) throw TimeLimitError(std::string(stage) + " did not stop in time");
      throw CancelledError(std::string(stage) + " was cancelled");
    case core::IsolatedResult::Status::crashed:
      throw std::runtime_error(std::string(stage) + " crashed (" + run.message + ")");
    case core::IsolatedResult::Status::failed:
      break;
  }
  throw std::runtime_error(run.message);
}

// The type of every Voronoi edge ("[0]", "[1s]", "[C]", "none", ...) as (element id, type)
// pairs, next to the graph's JSON: what the GUI colours the graph by.
py::tuple typed_voronoi(SolidPtr solid, const voronoi::VoronoiOptions& options, double sharp_angle,
                        py::object progress) {
  if (!solid) throw std::invalid_argument("no solid given");
  if (std::string why = options.validate(); !why.empty()) throw std::invalid_argument(why);
  decompose::DecomposeOptions d;
  d.sharp_angle = sharp_angle;
  if (std::string why = d.validate(); !why.empty()) throw std::invalid_argument(why);
  // The child sends "<id> <type>" lines, a 0x1e separator, then the graph's JSON.
  const std::string bytes = run_isolated(
      [&](const core::Progress&) {
        const voronoi::VoronoiResult graph = voronoi::compute_voronoi_graph(*solid, options);
        std::string out;
        for (const decompose::ClassifiedEdge& e : decompose::classify_edges(graph, d))
          out += std::to_string(e.element) + " " + decompose::detail::edge_type_name(e.type) + "\n";
        return out + '\x1e' + voronoi::voronoi_graph_json(graph);
      },
      progress, "voronoi_graph");
  const std::size_t sep = bytes.find('\x1e');
  if (sep == std::string::npos) throw std::runtime_error("the Voronoi graph came back garbled");
  std::vector<std::pair<int, std::string>> types;
  std::size_t at = 0;
  while (at < sep) {
    const std::size_t eol = bytes.find('\n', at);
    const std::string line = bytes.substr(at, eol - at);
    const std::size_t space = line.find(' ');
    types.emplace_back(std::stoi(line.substr(0, space)), line.substr(space + 1));
    at = eol + 1;
  }
  return py::make_tuple(bytes.substr(sep + 1), types);
}

// When a decomposition's child is killed where OCCT does not return (as in `vorohex
// decompose`).
double kill_after(double time_limit) {
  return time_limit + decompose::stop_grace(time_limit);
}

void check_time_limit(double time_limit) {
  if (!(std::isfinite(time_limit) && time_limit > 0))
    throw std::invalid_argument("time_limit must be a number of seconds > 0, got " +
                                std::to_string(time_limit));
}

// The decomposition as JSON text (decomposition_io.h layout), writing the sub-volumes as a
// BREP compound and the decomposition faces as VTP where paths are given.
std::string decomposition_json(SolidPtr solid, const voronoi::VoronoiOptions& graph_options,
                               double sharp_angle, bool merge, const std::string& brep_path,
                               const std::string& vtp_path, py::object progress, double time_limit,
                               bool multisweep, bool revolve) {
  if (!solid) throw std::invalid_argument("no solid given");
  if (std::string why = graph_options.validate(); !why.empty()) throw std::invalid_argument(why);
  decompose::DecomposeOptions options;
  options.sharp_angle = sharp_angle;
  options.merge = merge;
  options.multisweep = multisweep;
  options.revolve = revolve;
  if (std::string why = options.validate(); !why.empty()) throw std::invalid_argument(why);
  check_time_limit(time_limit);
  // In the child: it writes the files, the JSON comes back. The time limit bounds the whole
  // (decompose/decompose.h); a child that does not stop is killed a little after it.
  try {
    return run_isolated(
        [&](const core::Progress& in_child) {
          const core::Progress deadline = in_child.with_time_limit(time_limit);
          const voronoi::VoronoiResult graph =
              voronoi::compute_voronoi_graph(*solid, graph_options);
          const decompose::DecompositionResult result =
              decompose::decompose(*solid, graph, options, deadline);
          std::string error;
          if (result.ok() &&
              !decompose::write_decomposition(result, brep_path, "", &error, vtp_path))
            throw std::runtime_error(error);
          return decompose::decomposition_json(result);
        },
        progress, "decomposition", kill_after(time_limit));
  } catch (const TimeLimitError&) {
    decompose::DecompositionResult failed;  // status failed
    failed.diagnostics.push_back(decompose::not_stopped_error(time_limit));
    return decompose::decomposition_json(failed);
  }
}

// The solid as the one sub-volume, as JSON text (decompose::whole_solid_json), where the mesh
// pipeline takes it whole (decompose::whole_solid_scheme); "" where no scheme does.
std::string whole_solid_json(SolidPtr solid, bool multisweep, bool revolve) {
  if (!solid) throw std::invalid_argument("no solid given");
  decompose::DecomposeOptions options;
  options.multisweep = multisweep;
  options.revolve = revolve;
  std::string reason;
  std::pair<core::FaceId, core::FaceId> ends;
  const decompose::Scheme s = decompose::whole_solid_scheme(*solid, options, &reason, &ends);
  return s == decompose::Scheme::none
             ? ""
             : decompose::whole_solid_json(s, reason, solid->volume(), ends);
}

// The mesher's exact plane cuts at concave edges (decompose/plane_cuts.h) as JSON text
// (decomposition_io.h), each piece with the scheme it gets; writes the pieces as a BREP
// compound where a path is given (also when the cuts failed: the pieces as cut).
std::string plane_cuts_json(SolidPtr solid, const std::string& brep_path, py::object progress,
                            double time_limit, bool tangent_planes, bool merge, bool multisweep,
                            bool as_the_mesher) {
  if (!solid) throw std::invalid_argument("no solid given");
  check_time_limit(time_limit);
  decompose::PlaneCutOptions options;
  options.time_limit = time_limit;
  options.tangent_planes = tangent_planes;
  options.merge = merge;
  options.multisweep = multisweep;
  try {
    return run_isolated(
        [&](const core::Progress& in_child) {
          const core::Progress deadline = in_child.with_time_limit(time_limit);
          const decompose::PlaneCutResult cut =
              as_the_mesher ? decompose::cut_as_the_mesher(*solid, options, deadline)
                            : decompose::cut_at_concave_edges(*solid, options, deadline);
          if (!brep_path.empty() && !cut.pieces.empty()) {
            std::vector<const occ::Solid*> pieces;
            for (const occ::Solid& s : cut.pieces) pieces.push_back(&s);
            std::string error;
            if (!occ::write_compound_brep(pieces, brep_path, &error))
              throw std::runtime_error(error);
          }
          return decompose::plane_cuts_json(cut, decompose::plane_cut_schemes(cut, multisweep));
        },
        progress, "plane cuts", kill_after(time_limit));
  } catch (const TimeLimitError&) {
    decompose::PlaneCutResult failed;
    std::ostringstream s;
    s << "the cuts did not stop within their time limit of " << time_limit
      << " s (OCCT did not return in time) and were stopped " << decompose::stop_grace(time_limit)
      << " s after it";
    failed.why_not = s.str();
    return decompose::plane_cuts_json(failed, {});
  }
}

quality::CheckReport check(const core::HexMesh& mesh, SolidPtr solid, double volume_rel_tol,
                           double distance_rel_tol) {
  quality::CheckOptions o;
  o.volume_rel_tol = volume_rel_tol;
  o.distance_rel_tol = distance_rel_tol;
  o.validate();
  py::gil_scoped_release nogil;
  return quality::check_mesh(mesh, solid.get(), o);
}

}  // namespace

PYBIND11_MODULE(_VoroHexCore, m) {
  m.doc() = "VoroHex C++ core (all-hexahedral meshing); use the VoroHex module instead";
  py::register_exception<std::invalid_argument>(m, "InvalidArgument", PyExc_ValueError);
  py::register_exception<CancelledError>(m, "Cancelled", PyExc_RuntimeError);
  bind_types(m);
  bind_mesh(m);
  m.def("scheme_names", &vorohex::pipeline::scheme_names,
        "every single-solid scheme name MeshOptions.schemes accepts");
  m.def("read_brep", &read_brep, py::arg("brep"), py::arg("several_solids") = false,
        "BREP string -> (Solid or None, [Diagnostic]); several_solids: glue them into one");
  m.def("generate_mesh", &generate, py::arg("solid"), py::arg("options"),
        py::arg("progress") = py::none(), py::arg("cancel") = nullptr,
        "mesh a solid; progress(stage, fraction) may return False to cancel");
  m.def("voronoi_graph_json", &voronoi_json, py::arg("solid"), py::arg("options"),
        "the embedded Voronoi graph of a solid as JSON text");
  m.def("typed_voronoi_graph", &typed_voronoi, py::arg("solid"), py::arg("options"),
        py::arg("sharp_angle") = 60.0, py::arg("progress") = py::none(),
        "(graph JSON text, [(element id, edge type)]) for the GUI; computed in a child "
        "process, progress(stage, fraction) heartbeats may return False to cancel");
  m.def("decomposition_json", &decomposition_json, py::arg("solid"), py::arg("graph_options"),
        py::arg("sharp_angle"), py::arg("merge"), py::arg("brep_path") = "",
        py::arg("vtp_path") = "", py::arg("progress") = py::none(), py::arg("time_limit") = 30.0,
        py::arg("multisweep") = true, py::arg("revolve") = true,
        "the decomposition of a solid as JSON text; writes the sub-volumes (BREP) and the "
        "decomposition faces (VTP) where paths are given; time_limit: seconds for the whole; "
        "multisweep, revolve: whether those meshers judge the sub-volumes too");
  m.def("whole_solid_json", &whole_solid_json, py::arg("solid"), py::arg("multisweep") = true,
        py::arg("revolve") = true,
        "the solid as its one sub-volume (JSON text) where the mesher meshes it whole with one "
        "scheme; \"\" where none takes it");
  m.def("plane_cuts_json", &plane_cuts_json, py::arg("solid"), py::arg("brep_path") = "",
        py::arg("progress") = py::none(), py::arg("time_limit") = 30.0,
        py::arg("tangent_planes") = false, py::arg("merge") = true, py::arg("multisweep") = true,
        py::arg("as_the_mesher") = false,
        "the exact plane cuts at a solid's concave edges as JSON text, each piece with its "
        "scheme (merge=False: the pieces as cut; as_the_mesher: the tangent planes where the "
        "first cut's pieces have knife edges and do not all have a scheme); writes the pieces "
        "(BREP) where a path is given");
  m.def("check_mesh", &check, py::arg("mesh"), py::arg("solid") = nullptr,
        py::arg("volume_rel_tol") = quality::CheckOptions{}.volume_rel_tol,
        py::arg("distance_rel_tol") = quality::CheckOptions{}.distance_rel_tol);
  m.def(
      "read_mesh",
      [](const std::string& path) {
        io::ReadMeshResult r;
        {
          py::gil_scoped_release nogil;
          r = io::read_mesh(path);
        }
        auto mesh = std::make_shared<core::HexMesh>(std::move(r.mesh));
        return py::make_tuple(r.ok ? py::cast(mesh) : py::none(), diagnostics_list(r.diagnostics));
      },
      py::arg("path"), "-> (HexMesh or None, [Diagnostic])");
  m.def(
      "write_mesh",
      [](const core::HexMesh& mesh, const std::string& path, std::vector<double> scaled_jacobian) {
        io::WriteOptions o;
        o.scaled_jacobian = std::move(scaled_jacobian);
        std::string error;
        bool ok;
        {
          py::gil_scoped_release nogil;
          ok = io::write_mesh(mesh, path, o, &error);
        }
        if (!ok) throw std::runtime_error("cannot write " + path + ": " + error);
      },
      py::arg("mesh"), py::arg("path"), py::arg("scaled_jacobian") = std::vector<double>{});
  m.def(
      "write_result",
      [](const pipeline::MeshResult& r, const std::string& path, const std::string& element) {
        io::WriteOptions o;
        o.scaled_jacobian = r.scaled_jacobian;
        o.groups = r.groups;
        std::vector<core::Diagnostic> notes;
        std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        io::ElementChoiceOptions eo;
        eo.requested = element;
        if (!element.empty() && !io::parse_element_type(element))
          throw std::invalid_argument("unknown element type '" + element +
                                      "' (use C3D8, C3D8I, C3D8R, C3D20 or C3D20R)");
        if (!element.empty() && ext != ".inp")
          throw std::invalid_argument("the element type applies to .inp files only");
        if (ext == ".inp") {
          const io::ElementChoice choice = io::choose_element_type(r.mesh, r.scaled_jacobian, eo);
          notes = choice.diagnostics;
          if (!choice.ok) {
            std::string why;
            for (const auto& d : choice.diagnostics)
              if (d.severity == core::Severity::error) why += (why.empty() ? "" : "; ") + d.message;
            throw std::invalid_argument(why);
          }
          o.element = choice.type;
        }
        std::string error;
        bool ok;
        {
          py::gil_scoped_release nogil;
          ok = io::write_mesh(r.mesh, path, o, &error);
        }
        if (!ok) throw std::runtime_error("cannot write " + path + ": " + error);
        return diagnostics_list(notes);
      },
      py::arg("result"), py::arg("path"), py::arg("element") = std::string(),
      "writes a result with its named groups (and for .inp the element type: '' = the safe "
      "default); returns the element choice's diagnostics; ValueError when refused");
  m.attr("HISTOGRAM_BINS") = quality::QualityStats::kBins;
}
