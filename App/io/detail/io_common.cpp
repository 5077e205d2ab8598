#include "io/detail/io_common.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>

namespace vorohex::io::detail {

bool load_file(const std::string& path, std::string* data,
               std::vector<core::Diagnostic>* diagnostics) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    diagnostics->push_back(
        core::make_error("file_not_found", "Cannot open '" + path + "': " + std::strerror(errno)));
    return false;
  }
  data->clear();
  char chunk[1 << 16];
  std::size_t n;
  while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) data->append(chunk, n);
  const bool read_error = std::ferror(f) != 0;
  std::fclose(f);
  if (read_error) {
    diagnostics->push_back(core::make_error("file_not_found", "Cannot read '" + path + "'"));
    return false;
  }
  if (data->find_first_not_of(" \t\r\n") == std::string::npos) {
    diagnostics->push_back(core::make_error("empty_file", "The file '" + path + "' is empty"));
    return false;
  }
  return true;
}

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
}

bool OutputFile::open(const std::string& path, std::string* error) {
  path_ = path;
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) {
    set_error(error, "Cannot open '" + path + "' for writing: " + std::strerror(errno));
    return false;
  }
  buffer_.reserve(kFlushSize + (1 << 16));
  return true;
}

void OutputFile::flush() {
  if (!file_ || buffer_.empty()) return;
  if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) failed_ = true;
  buffer_.clear();
}

bool OutputFile::close(std::string* error) {
  if (!file_) {
    set_error(error, "File '" + path_ + "' is not open");
    return false;
  }
  flush();
  if (std::fclose(file_) != 0) failed_ = true;
  file_ = nullptr;
  if (failed_) set_error(error, "Writing '" + path_ + "' failed (disk full?)");
  return !failed_;
}

void append_double(std::string* s, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  s->append(buf, r.ptr);
}

void append_double_20(std::string* s, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 13);
  s->append(buf, r.ptr);
}

void append_int(std::string* s, std::int64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  s->append(buf, r.ptr);
}

bool check_hex_indices(const core::HexMesh& mesh, std::string* error) {
  const auto n = static_cast<std::int64_t>(mesh.num_nodes());
  const auto& hexes = mesh.hexes();
  for (std::size_t h = 0; h < hexes.size(); ++h)
    for (std::int32_t v : hexes[h])
      if (v < 0 || v >= n) {
        set_error(error, "Hexahedron " + std::to_string(h) + " refers to node " +
                             std::to_string(v) + " but the mesh has " + std::to_string(n) +
                             " nodes");
        return false;
      }
  const auto& mid = mesh.mid_edge_nodes();
  if (!mid.empty() && mid.size() != hexes.size()) {
    set_error(error, "The mesh has " + std::to_string(mid.size()) + " mid-edge node lists for " +
                         std::to_string(hexes.size()) + " hexahedra");
    return false;
  }
  for (std::size_t h = 0; h < mid.size(); ++h)
    for (std::int32_t v : mid[h])
      if (v < 0 || v >= n) {
        set_error(error, "Hexahedron " + std::to_string(h) + " refers to mid-edge node " +
                             std::to_string(v) + " but the mesh has " + std::to_string(n) +
                             " nodes");
        return false;
      }
  return true;
}

}  // namespace vorohex::io::detail
