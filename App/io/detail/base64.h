// Base64 (RFC 4648) for VTK XML binary data arrays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vorohex::io::detail {

// Characters needed to encode n bytes (with padding).
inline std::size_t base64_encoded_size(std::size_t n) {
  return (n + 2) / 3 * 4;
}

// Encodes n bytes to out (base64_encoded_size(n) characters, padded); returns the end.
char* base64_encode(const std::uint8_t* in, std::size_t n, char* out);

// Decodes [begin, end) and appends the bytes to *out. Whitespace is ignored, and '='
// padding ends one quantum without ending the stream, so concatenated base64 streams
// (VTK encodes a header and its data separately) decode to their concatenated bytes.
// Returns false on a character outside the alphabet or a dangling partial quantum.
bool base64_decode(const char* begin, const char* end, std::vector<std::uint8_t>* out);

}  // namespace vorohex::io::detail
