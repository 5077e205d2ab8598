#include "voronoi/graph_io.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace vorohex::voronoi {
namespace {

const char* status_name(VoronoiStatus s) {
  switch (s) {
    case VoronoiStatus::ok:
      return "ok";
    case VoronoiStatus::partial:
      return "partial";
    case VoronoiStatus::failed:
      return "failed";
  }
  return "?";
}

nlohmann::json point(const Vec3& p) {
  return nlohmann::json::array({p.x(), p.y(), p.z()});
}

std::string governor_names(const VoronoiElement& el) {
  std::string s;
  for (const EntityRef& g : el.governors) s += (s.empty() ? "" : " ") + g.name();
  return s;
}

int kind_code(ElementKind k) {
  return k == ElementKind::face ? 0 : k == ElementKind::edge ? 1 : 2;
}

std::string vtp_text(const VoronoiGraph& g) {
  // Point cells (vertices and faces) first, then polylines (edges), as VTK orders them.
  std::vector<int> point_cells, line_cells;
  for (int i = 0; i < int(g.elements.size()); ++i) {
    const VoronoiElement& el = g.elements[i];
    if (el.kind == ElementKind::edge && el.polyline.size() >= 2)
      line_cells.push_back(i);
    else
      point_cells.push_back(i);
  }
  std::ostringstream pts, conn, offs, lconn, loffs;
  pts.precision(12);
  int np = 0, off = 0, loff = 0;
  for (int i : point_cells) {
    const Vec3& p = g.elements[i].point;
    pts << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    conn << np++ << ' ';
    offs << ++off << ' ';
  }
  for (int i : line_cells) {
    for (const Vec3& p : g.elements[i].polyline) {
      pts << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
      lconn << np++ << ' ';
    }
    loff += int(g.elements[i].polyline.size());
    loffs << loff << ' ';
  }
  std::vector<int> order = point_cells;
  order.insert(order.end(), line_cells.begin(), line_cells.end());
  std::ostringstream kind, fs, ids;
  for (int i : order) {
    const VoronoiElement& el = g.elements[i];
    kind << kind_code(el.kind) << ' ';
    fs << (el.fs ? 1 : 0) << ' ';
    ids << i << ' ';
  }
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<PolyData>\n"
      << "<Piece NumberOfPoints=\"" << np << "\" NumberOfVerts=\"" << point_cells.size()
      << "\" NumberOfLines=\"" << line_cells.size()
      << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
      << pts.str() << "</DataArray></Points>\n"
      << "<Verts>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" << conn.str()
      << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" << offs.str()
      << "</DataArray>\n</Verts>\n"
      << "<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" << lconn.str()
      << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" << loffs.str()
      << "</DataArray>\n</Lines>\n"
      << "<CellData Scalars=\"kind\">\n"
      << "<DataArray type=\"Int32\" Name=\"kind\" format=\"ascii\">" << kind.str()
      << "</DataArray>\n"
      << "<DataArray type=\"Int32\" Name=\"f_s\" format=\"ascii\">" << fs.str() << "</DataArray>\n"
      << "<DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">" << ids.str() << "</DataArray>\n"
      << "<DataArray type=\"String\" Name=\"governors\" NumberOfTuples=\"" << order.size()
      << "\" format=\"ascii\">\n";
  // ASCII string arrays: each string as its character codes followed by a 0.
  for (int i : order) {
    std::string s = governor_names(g.elements[i]);
    for (unsigned char c : s) out << int(c) << ' ';
    out << "0\n";
  }
  out << "</DataArray>\n</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return out.str();
}

}  // namespace

std::string voronoi_graph_json(const VoronoiResult& result) {
  nlohmann::json j;
  nlohmann::json elements = nlohmann::json::array();
  int nv = 0, ne = 0, nf = 0, nfs = 0;
  const VoronoiGraph& g = result.graph;
  for (int i = 0; i < int(g.elements.size()); ++i) {
    const VoronoiElement& el = g.elements[i];
    nlohmann::json e;
    e["id"] = i;
    e["kind"] = element_kind_name(el.kind);
    nlohmann::json govs = nlohmann::json::array();
    for (const EntityRef& gv : el.governors) govs.push_back(gv.name());
    e["governors"] = govs;
    e["point"] = point(el.point);
    e["radius"] = el.radius;
    e["verified"] = el.verified;
    if (el.kind == ElementKind::face) {
      e["f_s"] = el.fs;
      ++nf;
      nfs += el.fs;
    }
    if (el.kind == ElementKind::edge) {
      ++ne;
      nlohmann::json poly = nlohmann::json::array();
      for (const Vec3& p : el.polyline) poly.push_back(point(p));
      e["polyline"] = poly;
    }
    if (el.kind == ElementKind::vertex) ++nv;
    e["incident"] = el.incident;
    elements.push_back(std::move(e));
  }
  j["elements"] = std::move(elements);
  j["counts"] = {{"vertices", nv}, {"edges", ne}, {"faces", nf}, {"f_s", nfs}};
  const VoronoiStats& s = result.stats;
  j["stats"] = {{"cells", s.cells},
                {"leaves", s.leaves},
                {"finest_cells", s.finest_cells},
                {"finest_level", s.finest_level},
                {"distance_evaluations", s.distance_evaluations},
                {"seconds", s.seconds},
                {"model_seconds", s.model_seconds}};
  j["status"] = status_name(result.status);
  nlohmann::json diags = nlohmann::json::array();
  for (const core::Diagnostic& d : result.diagnostics)
    diags.push_back({{"severity", core::severity_name(d.severity)},
                     {"code", d.code},
                     {"message", d.message},
                     {"entities", d.entities}});
  j["diagnostics"] = std::move(diags);
  return j.dump(1);
}

bool write_voronoi_graph(const VoronoiResult& result, const std::string& json_path,
                         const std::string& vtp_path, std::string* error) {
  auto write = [&](const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    if (f) f << text;
    if (!f) {
      if (error) *error = "cannot write " + path;
      return false;
    }
    return true;
  };
  if (!write(json_path, voronoi_graph_json(result))) return false;
  if (!vtp_path.empty() && !write(vtp_path, vtp_text(result.graph))) return false;
  return true;
}

}  // namespace vorohex::voronoi
