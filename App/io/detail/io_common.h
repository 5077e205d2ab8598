// File reading, buffered writing and checks shared by the mesh readers and writers.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"

namespace vorohex::io::detail {

// Reads the whole file; on failure appends a file_not_found / empty_file error.
bool load_file(const std::string& path, std::string* data,
               std::vector<core::Diagnostic>* diagnostics);

// The extension without the dot, lower case ("" if none).
std::string lower_extension(const std::string& path);

// Buffered writer on a FILE*: callers fill text() and call flush_if_full() now and then.
class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();

  bool open(const std::string& path, std::string* error);
  std::string& text() { return buffer_; }
  void write(std::string_view s) { buffer_.append(s); }
  void flush_if_full() {
    if (buffer_.size() >= kFlushSize) flush();
  }
  void flush();
  // Flushes, closes and reports write errors (disk full, ...).
  bool close(std::string* error);

  static constexpr std::size_t kFlushSize = 1 << 22;

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::string buffer_;
  bool failed_ = false;
};

// Shortest text that reads back to the same double (std::to_chars).
void append_double(std::string* s, double v);
// 13 significant digits, at most 20 characters: for formats whose readers take
// fixed-width fields, e.g. CalculiX, which reads a number in 20 characters and refused
// "1.4145660816281972E-30" (a coordinate that is zero up to rounding).
void append_double_20(std::string* s, double v);
void append_int(std::string* s, std::int64_t v);

// False (with *error set) if a hexahedron refers to a node that does not exist.
bool check_hex_indices(const core::HexMesh& mesh, std::string* error);

inline void set_error(std::string* error, const std::string& message) {
  if (error) *error = message;
}

}  // namespace vorohex::io::detail
