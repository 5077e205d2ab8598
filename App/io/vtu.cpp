// VTK XML UnstructuredGrid (.vtu) for ParaView.
//
// Writer: version 1.0, LittleEndian, header_type UInt64, inline base64 ("binary"), one
// header per array; the header and the data are encoded as one base64 stream, as VTK does
// for uncompressed arrays. Reader: ascii, binary and appended (raw or base64), zlib or not.
// In VTU files `offsets` holds the end of each cell's connectivity (no leading 0).
#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>

#include "io/detail/base64.h"
#include "io/detail/io_common.h"
#include "io/detail/vtu_arrays.h"
#include "io/detail/xml_scan.h"
#include "io/mesh_io.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::io {
namespace {

using detail::OutputFile;

constexpr std::uint8_t kVtkHexahedron = 12;
constexpr std::uint8_t kVtkQuadraticHexahedron = 25;  // 8 corners, 12 mid-edge nodes

// Encodes everything appended to it as one base64 stream, in large chunks.
class Base64Stream {
 public:
  explicit Base64Stream(OutputFile* out) : out_(out), raw_(kRaw) {}

  void append(const void* data, std::size_t n) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    while (n > 0) {
      const std::size_t take = std::min(n, kRaw - used_);
      std::memcpy(raw_.data() + used_, p, take);
      used_ += take;
      p += take;
      n -= take;
      if (used_ == kRaw) encode();
    }
  }
  void finish() { encode(); }

 private:
  void encode() {
    std::string& t = out_->text();
    const std::size_t old = t.size();
    t.resize(old + detail::base64_encoded_size(used_));
    detail::base64_encode(raw_.data(), used_, t.data() + old);
    used_ = 0;
    out_->flush_if_full();
  }

  static constexpr std::size_t kRaw = 3 * (1 << 16);  // a multiple of 3: no inner padding
  OutputFile* out_;
  std::vector<std::uint8_t> raw_;
  std::size_t used_ = 0;
};

template <class T>
T to_little_endian(T v) {
  if constexpr (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__ && sizeof(T) > 1) {
    std::uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    std::reverse(b, b + sizeof(T));
    std::memcpy(&v, b, sizeof(T));
  }
  return v;
}

// One <DataArray format="binary">: UInt64 byte count, then count values get(i).
template <class T, class Get>
void write_array(OutputFile* out, const char* type, const char* name, int components,
                 std::size_t count, Get get) {
  std::string& t = out->text();
  t += "        <DataArray type=\"";
  t += type;
  t += "\" Name=\"";
  t += name;
  t += "\" NumberOfComponents=\"";
  detail::append_int(&t, components);
  t += "\" format=\"binary\">\n          ";
  Base64Stream stream(out);
  const std::uint64_t nbytes = to_little_endian<std::uint64_t>(count * sizeof(T));
  stream.append(&nbytes, sizeof nbytes);
  T batch[4096];
  for (std::size_t i = 0; i < count;) {
    const std::size_t n = std::min<std::size_t>(4096, count - i);
    for (std::size_t k = 0; k < n; ++k) batch[k] = to_little_endian<T>(get(i + k));
    stream.append(batch, n * sizeof(T));
    i += n;
  }
  stream.finish();
  out->write("\n        </DataArray>\n");
}

}  // namespace

bool write_vtu(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
               std::string* error) {
  if (!detail::check_hex_indices(mesh, error)) return false;
  const std::size_t nn = mesh.num_nodes();
  const std::size_t nh = mesh.num_hexes();
  if (!options.scaled_jacobian.empty() && options.scaled_jacobian.size() != nh) {
    detail::set_error(error, "WriteOptions::scaled_jacobian has " +
                                 std::to_string(options.scaled_jacobian.size()) +
                                 " values but the mesh has " + std::to_string(nh) + " hexahedra");
    return false;
  }
  std::vector<double> computed;
  if (options.scaled_jacobian.empty() && nh > 0) computed = quality::scaled_jacobians(mesh);
  const std::vector<double>& sj =
      options.scaled_jacobian.empty() ? computed : options.scaled_jacobian;

  OutputFile out;
  if (!out.open(path, error)) return false;
  std::string& t = out.text();
  t += "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"";
  detail::append_int(&t, static_cast<std::int64_t>(nn));
  t += "\" NumberOfCells=\"";
  detail::append_int(&t, static_cast<std::int64_t>(nh));
  t += "\">\n      <PointData Scalars=\"ClassDim\">\n";
  const auto& classes = mesh.node_classes();
  write_array<std::int8_t>(&out, "Int8", "ClassDim", 1, nn,
                           [&](std::size_t i) { return classes[i].dim; });
  write_array<std::int32_t>(&out, "Int32", "ClassId", 1, nn,
                            [&](std::size_t i) { return classes[i].id; });
  out.write("      </PointData>\n      <CellData Scalars=\"SubVolume\">\n");
  const auto& sub = mesh.sub_volumes();
  write_array<std::int32_t>(&out, "Int32", "SubVolume", 1, nh,
                            [&](std::size_t i) { return sub[i]; });
  write_array<double>(&out, "Float64", "ScaledJacobian", 1, nh,
                      [&](std::size_t i) { return sj[i]; });
  out.write("      </CellData>\n      <Points>\n");
  const auto& points = mesh.points();
  write_array<double>(&out, "Float64", "Points", 3, 3 * nn,
                      [&](std::size_t i) { return points[i / 3][static_cast<int>(i % 3)]; });
  out.write("      </Points>\n      <Cells>\n");
  const auto& hexes = mesh.hexes();
  const auto& mid = mesh.mid_edge_nodes();
  const std::size_t per = mesh.order() == 2 ? 20 : 8;
  write_array<std::int64_t>(&out, "Int64", "connectivity", 1, per * nh, [&](std::size_t i) {
    const std::size_t h = i / per, k = i % per;
    return static_cast<std::int64_t>(k < 8 ? hexes[h][k] : mid[h][k - 8]);
  });
  write_array<std::int64_t>(&out, "Int64", "offsets", 1, nh, [&](std::size_t i) {
    return static_cast<std::int64_t>(per * (i + 1));
  });
  const std::uint8_t type = per == 20 ? kVtkQuadraticHexahedron : kVtkHexahedron;
  write_array<std::uint8_t>(&out, "UInt8", "types", 1, nh, [&](std::size_t) { return type; });
  out.write("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  return out.close(error);
}

namespace {

using detail::kNoElement;
using detail::VtuLayout;
using detail::XmlDocument;

class VtuReader {
 public:
  VtuReader(const std::string& data, ReadMeshResult* result) : data_(data), result_(result) {}

  bool read() {
    std::string why;
    if (!detail::scan_xml(data_, "AppendedData", &doc_, &why)) return fail(why);
    const detail::XmlElement& root = doc_.elements[0];
    if (root.name != "VTKFile")
      return fail("the root element is <" + root.name + ">, not <VTKFile>");
    const std::string* type = root.attribute("type");
    if (!type || *type != "UnstructuredGrid")
      return fail("not an UnstructuredGrid file (type=\"" + (type ? *type : std::string()) + "\")");
    if (!read_layout()) return false;
    const std::size_t grid = doc_.child_named(0, "UnstructuredGrid");
    if (grid == kNoElement) return fail("no <UnstructuredGrid> element");
    const auto pieces = doc_.children_named(grid, "Piece");
    if (pieces.empty()) return fail("no <Piece> element");
    for (std::size_t piece : pieces)
      if (!read_piece(piece)) return false;
    if (result_->mesh.num_hexes() == 0) {
      return fail("the file contains no hexahedron" +
                  (skipped_ ? " (" + std::to_string(skipped_) + " other cells)" : std::string()));
    }
    if (skipped_ > 0)
      result_->diagnostics.push_back(core::make_warning(
          "non_hex_cells_skipped", "Skipped " + std::to_string(skipped_) +
                                       " cells that are not hexahedra (kept " +
                                       std::to_string(result_->mesh.num_hexes()) + ")"));
    return true;
  }

 private:
  bool fail(const std::string& what) {
    result_->diagnostics.push_back(core::make_error("unreadable_mesh", "VTU: " + what));
    return false;
  }

  bool read_layout() {
    const detail::XmlElement& root = doc_.elements[0];
    layout_.file = data_;
    const std::string* header = root.attribute("header_type");
    if (header && *header != "UInt32" && *header != "UInt64")
      return fail("unsupported header_type " + *header);
    layout_.header_uint64 = header && *header == "UInt64";
    const std::string* order = root.attribute("byte_order");
    if (order && *order != "LittleEndian" && *order != "BigEndian")
      return fail("unsupported byte_order " + *order);
    layout_.big_endian = order && *order == "BigEndian";
    const std::string* compressor = root.attribute("compressor");
    if (compressor && !compressor->empty()) {
      if (*compressor != "vtkZLibDataCompressor")
        return fail("unsupported compressor " + *compressor + " (only zlib is supported)");
      layout_.zlib = true;
    }
    if (doc_.opaque_element == kNoElement) return true;
    const detail::XmlElement& appended = doc_.elements[doc_.opaque_element];
    const std::string* encoding = appended.attribute("encoding");
    if (encoding && *encoding != "raw" && *encoding != "base64")
      return fail("unsupported AppendedData encoding " + *encoding);
    layout_.appended_raw = !encoding || *encoding == "raw";
    const std::size_t marker = data_.find('_', appended.content_begin);
    if (marker == std::string::npos) return fail("<AppendedData> has no '_' marker");
    layout_.appended_begin = marker + 1;
    const std::size_t end_tag = data_.rfind("</AppendedData>");
    layout_.appended_end =
        end_tag != std::string::npos && end_tag >= layout_.appended_begin ? end_tag : data_.size();
    for (const auto& e : doc_.elements) {
      const std::string* format = e.attribute("format");
      const std::string* offset = e.attribute("offset");
      std::uint64_t v = 0;
      if (e.name == "DataArray" && format && *format == "appended" && offset &&
          std::from_chars(offset->data(), offset->data() + offset->size(), v).ec == std::errc())
        layout_.appended_offsets.push_back(v);
    }
    std::sort(layout_.appended_offsets.begin(), layout_.appended_offsets.end());
    return true;
  }

  bool count_attribute(std::size_t element, const char* key, std::size_t limit, std::size_t* v) {
    const std::string* s = doc_.elements[element].attribute(key);
    std::uint64_t x = 0;
    if (!s || std::from_chars(s->data(), s->data() + s->size(), x).ec != std::errc())
      return fail(std::string("missing or invalid ") + key);
    if (x > limit) return fail(std::string(key) + " is too large (" + *s + ")");
    *v = static_cast<std::size_t>(x);
    return true;
  }

  // The DataArray of `parent` named `name` (or the first one when name is empty).
  std::size_t array(std::size_t parent, const std::string& name) const {
    if (parent == kNoElement) return kNoElement;
    for (std::size_t c : doc_.children_named(parent, "DataArray")) {
      if (name.empty()) return c;
      const std::string* n = doc_.elements[c].attribute("Name");
      if (n && *n == name) return c;
    }
    return kNoElement;
  }

  template <class T>
  bool read_array(std::size_t element, std::size_t count, int components, std::vector<T>* out) {
    std::string why;
    if (!detail::read_data_array(doc_, element, layout_, count, components, out, &why))
      return fail(why);
    return true;
  }

  bool read_piece(std::size_t piece) {
    core::HexMesh& mesh = result_->mesh;
    const std::size_t max_nodes = std::numeric_limits<std::int32_t>::max() - mesh.num_nodes();
    std::size_t np = 0, nc = 0;
    if (!count_attribute(piece, "NumberOfPoints", max_nodes, &np) ||
        !count_attribute(piece, "NumberOfCells", std::numeric_limits<std::int32_t>::max(), &nc))
      return false;
    // Points.
    std::vector<double> xyz;
    if (np > 0) {
      const std::size_t points = array(doc_.child_named(piece, "Points"), "");
      if (points == kNoElement) return fail("a piece has no <Points> data");
      if (!read_array(points, 3 * np, 3, &xyz)) return false;
    }
    // Cells.
    std::vector<std::int64_t> offsets, types, connectivity;
    if (nc > 0) {
      const std::size_t cells = doc_.child_named(piece, "Cells");
      const std::size_t off = array(cells, "offsets");
      const std::size_t typ = array(cells, "types");
      const std::size_t con = array(cells, "connectivity");
      if (off == kNoElement || typ == kNoElement || con == kNoElement)
        return fail("<Cells> needs connectivity, offsets and types arrays");
      if (!read_array(off, nc, 1, &offsets) || !read_array(typ, nc, 1, &types)) return false;
      std::int64_t previous = 0;
      for (std::int64_t o : offsets) {
        if (o < previous) return fail("cell offsets decrease or are negative");
        previous = o;
      }
      if (previous > (std::int64_t(1) << 36)) return fail("cell offsets are implausibly large");
      if (!read_array(con, static_cast<std::size_t>(previous), 1, &connectivity)) return false;
    }
    // Point data (optional).
    const std::size_t point_data = doc_.child_named(piece, "PointData");
    std::vector<std::int64_t> class_dim, class_id, sub_volume;
    const std::size_t dim_array = array(point_data, "ClassDim");
    const std::size_t id_array = array(point_data, "ClassId");
    if (dim_array != kNoElement && !read_array(dim_array, np, 1, &class_dim)) return false;
    if (id_array != kNoElement && !read_array(id_array, np, 1, &class_id)) return false;
    const std::size_t sub_array = array(doc_.child_named(piece, "CellData"), "SubVolume");
    if (sub_array != kNoElement && !read_array(sub_array, nc, 1, &sub_volume)) return false;

    const auto offset = static_cast<std::int32_t>(mesh.num_nodes());
    std::size_t bad_class = 0;
    for (std::size_t i = 0; i < np; ++i) {
      core::NodeClass c = core::NodeClass::interior();
      if (!class_dim.empty()) {
        const std::int64_t d = class_dim[i];
        const std::int64_t id = class_id.empty() ? 0 : class_id[i];
        if (d >= 0 && d <= 3 && id >= 0 && id <= std::numeric_limits<std::int32_t>::max())
          c = {static_cast<std::int8_t>(d), static_cast<std::int32_t>(id)};
        else
          ++bad_class;
      }
      mesh.add_node(core::Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]), c);
    }
    if (bad_class)
      result_->diagnostics.push_back(core::make_warning(
          "invalid_classification",
          std::to_string(bad_class) + " nodes have an invalid ClassDim/ClassId; read as interior"));
    for (std::size_t c = 0; c < nc; ++c) {
      const std::int64_t begin = c == 0 ? 0 : offsets[c - 1];
      const std::int64_t end = offsets[c];
      if (types[c] != kVtkHexahedron && types[c] != kVtkQuadraticHexahedron) {
        ++skipped_;
        continue;
      }
      const int per = types[c] == kVtkHexahedron ? 8 : 20;
      if (end - begin != per)
        return fail("hexahedron " + std::to_string(c) + " has " + std::to_string(end - begin) +
                    " nodes, not " + std::to_string(per));
      std::array<std::int32_t, 20> nodes{};
      for (int k = 0; k < per; ++k) {
        const std::int64_t v = connectivity[static_cast<std::size_t>(begin + k)];
        if (v < 0 || v >= static_cast<std::int64_t>(np))
          return fail("cell " + std::to_string(c) + " refers to point " + std::to_string(v) +
                      " of " + std::to_string(np));
        nodes[k] = static_cast<std::int32_t>(v) + offset;
      }
      core::HexNodes h;
      std::copy(nodes.begin(), nodes.begin() + 8, h.begin());
      if (per == 20) {
        core::MidEdgeNodes m;
        std::copy(nodes.begin() + 8, nodes.end(), m.begin());
        mid_.push_back(m);
      } else {
        ++linear_;
      }
      std::int32_t sv = 0;
      if (!sub_volume.empty()) {
        const std::int64_t s = sub_volume[c];
        if (s < std::numeric_limits<std::int32_t>::min() ||
            s > std::numeric_limits<std::int32_t>::max())
          return fail("SubVolume value out of range");
        sv = static_cast<std::int32_t>(s);
      }
      mesh.add_hex(h, sv);
    }
    return true;
  }

  const std::string& data_;
  ReadMeshResult* result_;
  XmlDocument doc_;
  VtuLayout layout_;
  std::size_t skipped_ = 0;

 public:
  std::vector<core::MidEdgeNodes> mid_;  // of the 20-node hexahedra read
  std::size_t linear_ = 0;               // 8-node hexahedra read
};

}  // namespace

ReadMeshResult read_vtu(const std::string& path) {
  ReadMeshResult result;
  std::string data;
  if (!detail::load_file(path, &data, &result.diagnostics)) return result;
  VtuReader reader(data, &result);
  result.ok = reader.read();
  if (result.ok && !reader.mid_.empty()) {
    if (reader.linear_ > 0) {
      result.ok = false;
      result.diagnostics.push_back(core::make_error(
          "mixed_element_orders", "the file mixes " + std::to_string(reader.linear_) +
                                      " 8-node and " + std::to_string(reader.mid_.size()) +
                                      " 20-node hexahedra"));
    } else {
      result.mesh.set_mid_edge_nodes(std::move(reader.mid_));
    }
  }
  if (!result.ok) result.mesh = core::HexMesh();
  return result;
}

}  // namespace vorohex::io
