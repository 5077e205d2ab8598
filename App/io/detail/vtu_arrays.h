// Decoding of VTK XML <DataArray> elements: ascii, inline base64 and appended (raw or
// base64), optionally zlib-compressed (vtkZLibDataCompressor block layout), with UInt32 or
// UInt64 headers. Every size is checked against the bytes present before use.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/detail/xml_scan.h"

namespace vorohex::io::detail {

struct VtuLayout {
  std::string_view file;                        // the whole file
  bool header_uint64 = false;                   // header_type="UInt64" (else UInt32)
  bool big_endian = false;                      // byte_order="BigEndian"
  bool zlib = false;                            // compressor="vtkZLibDataCompressor"
  bool appended_raw = true;                     // <AppendedData encoding="raw"> (else base64)
  std::size_t appended_begin = 0;               // first byte after the '_' marker
  std::size_t appended_end = 0;                 // end of the appended block
  std::vector<std::uint64_t> appended_offsets;  // sorted offsets of all appended arrays
};

// Reads `count` values (count = tuples * components, checked against
// NumberOfComponents == components) of any numeric type.
bool read_data_array(const XmlDocument& doc, std::size_t element, const VtuLayout& layout,
                     std::size_t count, int components, std::vector<double>* out,
                     std::string* error);
// The same for integer arrays (floating-point arrays are rejected).
bool read_data_array(const XmlDocument& doc, std::size_t element, const VtuLayout& layout,
                     std::size_t count, int components, std::vector<std::int64_t>* out,
                     std::string* error);

}  // namespace vorohex::io::detail
