#include "io/detail/vtu_arrays.h"

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <type_traits>

#include "io/detail/base64.h"

namespace vorohex::io::detail {
namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, i64, u64, f32, f64 };

bool parse_scalar(const std::string& s, Scalar* t, std::size_t* size) {
  static const struct {
    const char* name;
    Scalar type;
    std::size_t size;
  } kTypes[] = {
      {"Int8", Scalar::i8, 1},     {"UInt8", Scalar::u8, 1},   {"Int16", Scalar::i16, 2},
      {"UInt16", Scalar::u16, 2},  {"Int32", Scalar::i32, 4},  {"UInt32", Scalar::u32, 4},
      {"Int64", Scalar::i64, 8},   {"UInt64", Scalar::u64, 8}, {"Float32", Scalar::f32, 4},
      {"Float64", Scalar::f64, 8}, {"Char", Scalar::i8, 1},    {"UChar", Scalar::u8, 1},
      {"Short", Scalar::i16, 2},   {"UShort", Scalar::u16, 2}, {"Int", Scalar::i32, 4},
      {"UInt", Scalar::u32, 4},    {"Float", Scalar::f32, 4},  {"Double", Scalar::f64, 8}};
  for (const auto& k : kTypes)
    if (s == k.name) {
      *t = k.type;
      *size = k.size;
      return true;
    }
  return false;
}

bool is_float(Scalar t) {
  return t == Scalar::f32 || t == Scalar::f64;
}

std::uint64_t load_uint(const std::uint8_t* p, std::size_t size, bool big_endian) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < size; ++i) {
    const std::size_t k = big_endian ? i : size - 1 - i;
    v = (v << 8) | p[k];
  }
  return v;
}

// Converts `count` little- (or big-) endian values of type t at p into out.
template <class T>
void convert(const std::uint8_t* p, Scalar t, std::size_t size, std::size_t count, bool big_endian,
             std::vector<T>* out) {
  out->resize(count);
  std::uint8_t b[8];
  for (std::size_t i = 0; i < count; ++i, p += size) {
    for (std::size_t k = 0; k < size; ++k) b[k] = big_endian ? p[size - 1 - k] : p[k];
    // The host is little-endian on every platform FreeCAD ships for; memcpy keeps it exact.
    T v{};
    switch (t) {
      case Scalar::i8: {
        std::int8_t x;
        std::memcpy(&x, b, 1);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::u8: {
        std::uint8_t x;
        std::memcpy(&x, b, 1);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::i16: {
        std::int16_t x;
        std::memcpy(&x, b, 2);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::u16: {
        std::uint16_t x;
        std::memcpy(&x, b, 2);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::i32: {
        std::int32_t x;
        std::memcpy(&x, b, 4);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::u32: {
        std::uint32_t x;
        std::memcpy(&x, b, 4);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::i64: {
        std::int64_t x;
        std::memcpy(&x, b, 8);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::u64: {
        std::uint64_t x;
        std::memcpy(&x, b, 8);
        // Values above INT64_MAX become -1 so that range checks reject them.
        if constexpr (std::is_integral_v<T>)
          v = x > static_cast<std::uint64_t>(INT64_MAX) ? T(-1) : static_cast<T>(x);
        else
          v = static_cast<T>(x);
        break;
      }
      case Scalar::f32: {
        float x;
        std::memcpy(&x, b, 4);
        v = static_cast<T>(x);
        break;
      }
      case Scalar::f64: {
        double x;
        std::memcpy(&x, b, 8);
        v = static_cast<T>(x);
        break;
      }
    }
    (*out)[i] = v;
  }
}

// Extracts the payload (header + data, maybe compressed) starting at `p` with `n` bytes
// available; `want` is the exact payload size expected.
bool extract_payload(const std::uint8_t* p, std::size_t n, const VtuLayout& layout,
                     std::size_t want, std::vector<std::uint8_t>* payload,
                     const std::uint8_t** data, std::string* error) {
  const std::size_t hs = layout.header_uint64 ? 8 : 4;
  if (n < hs) {
    *error = "data ends before its header";
    return false;
  }
  if (!layout.zlib) {
    const std::uint64_t nbytes = load_uint(p, hs, layout.big_endian);
    if (nbytes != want) {
      *error = "data holds " + std::to_string(nbytes) + " bytes, expected " + std::to_string(want);
      return false;
    }
    if (nbytes > n - hs) {
      *error = "data is truncated (" + std::to_string(n - hs) + " of " + std::to_string(nbytes) +
               " bytes)";
      return false;
    }
    *data = p + hs;
    return true;
  }
  // vtkZLibDataCompressor: [nblocks, block size, last block size, compressed sizes...].
  if (n < 3 * hs) {
    *error = "compressed data ends inside its header";
    return false;
  }
  const std::uint64_t nblocks = load_uint(p, hs, layout.big_endian);
  const std::uint64_t block = load_uint(p + hs, hs, layout.big_endian);
  const std::uint64_t last = load_uint(p + 2 * hs, hs, layout.big_endian);
  if (nblocks > (n - 3 * hs) / hs) {
    *error = "compressed header announces " + std::to_string(nblocks) + " blocks, too many";
    return false;
  }
  if (nblocks > 1 && block > want / (nblocks - 1)) {
    *error = "compressed header announces more data than expected";
    return false;
  }
  const std::uint64_t last_size = last == 0 ? block : last;
  const std::uint64_t total = nblocks == 0 ? 0 : (nblocks - 1) * block + last_size;
  if ((nblocks > 0 && (block == 0 || last_size > block || block > (std::uint64_t(1) << 40))) ||
      total != want) {
    *error = "compressed data holds " + std::to_string(total) + " bytes, expected " +
             std::to_string(want);
    return false;
  }
  std::size_t pos = (3 + nblocks) * hs;
  payload->assign(want, 0);
  for (std::uint64_t b = 0; b < nblocks; ++b) {
    const std::uint64_t csize = load_uint(p + (3 + b) * hs, hs, layout.big_endian);
    if (csize > n - pos) {
      *error = "compressed block " + std::to_string(b) + " is truncated";
      return false;
    }
    const std::uint64_t usize = b + 1 == nblocks ? last_size : block;
    uLongf dest = static_cast<uLongf>(usize);
    const int rc =
        uncompress(payload->data() + b * block, &dest, p + pos, static_cast<uLong>(csize));
    if (rc != Z_OK || dest != usize) {
      *error = "zlib cannot decompress block " + std::to_string(b) + " (" +
               (rc == Z_OK ? std::string("short block") : std::string(zError(rc))) + ")";
      return false;
    }
    pos += csize;
  }
  *data = payload->data();
  return true;
}

template <class T>
bool parse_ascii(std::string_view text, std::size_t count, Scalar t, std::vector<T>* out,
                 std::string* error) {
  out->clear();
  out->reserve(std::min(count, text.size() / 2 + 1));
  const char* p = text.data();
  const char* end = p + text.size();
  while (out->size() < count) {
    while (p < end && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')) ++p;
    if (p == end) break;
    if (*p == '+') ++p;
    T v{};
    std::from_chars_result r;
    if constexpr (std::is_integral_v<T>) {
      if (is_float(t)) {
        *error = "a floating-point array where integers are expected";
        return false;
      }
      r = std::from_chars(p, end, v);
    } else {
      r = std::from_chars(p, end, v);
    }
    if (r.ec != std::errc() ||
        (r.ptr != end && !(*r.ptr == ' ' || *r.ptr == '\n' || *r.ptr == '\r' || *r.ptr == '\t'))) {
      *error = "invalid number '" + std::string(p, std::min<std::size_t>(end - p, 20)) + "'";
      return false;
    }
    out->push_back(v);
    p = r.ptr;
  }
  if (out->size() < count) {
    *error = "has " + std::to_string(out->size()) + " values, expected " + std::to_string(count);
    return false;
  }
  return true;
}

template <class T>
bool read_array(const XmlDocument& doc, std::size_t element, const VtuLayout& layout,
                std::size_t count, int components, std::vector<T>* out, std::string* error) {
  const XmlElement& e = doc.elements[element];
  const std::string* name = e.attribute("Name");
  const std::string label = "DataArray" + (name ? " '" + *name + "'" : std::string()) + ": ";
  std::string why;
  auto fail = [&](const std::string& what) {
    *error = label + what;
    return false;
  };
  const std::string* type_name = e.attribute("type");
  Scalar t;
  std::size_t size = 0;
  if (!type_name || !parse_scalar(*type_name, &t, &size))
    return fail("unsupported type '" + (type_name ? *type_name : std::string()) + "'");
  if constexpr (std::is_integral_v<T>)
    if (is_float(t)) return fail("expected integers, found " + *type_name);
  int have_components = 1;
  if (const std::string* nc = e.attribute("NumberOfComponents")) {
    const auto r = std::from_chars(nc->data(), nc->data() + nc->size(), have_components);
    if (r.ec != std::errc()) return fail("invalid NumberOfComponents");
  }
  if (have_components != components)
    return fail("has " + std::to_string(have_components) + " components, expected " +
                std::to_string(components));
  if (count > (std::size_t(1) << 40) / size) return fail("too many values");
  const std::size_t want = count * size;
  const std::string* format = e.attribute("format");
  const std::string fmt = format ? *format : "ascii";
  const std::string_view content =
      layout.file.substr(e.content_begin, e.content_end - e.content_begin);

  if (fmt == "ascii") {
    if (!parse_ascii(content, count, t, out, &why)) return fail(why);
    return true;
  }
  std::vector<std::uint8_t> decoded, payload;
  const std::uint8_t* data = nullptr;
  if (fmt == "binary") {
    if (!base64_decode(content.data(), content.data() + content.size(), &decoded))
      return fail("invalid base64 data");
    if (!extract_payload(decoded.data(), decoded.size(), layout, want, &payload, &data, &why))
      return fail(why);
  } else if (fmt == "appended") {
    const std::string* off = e.attribute("offset");
    std::uint64_t offset = 0;
    if (!off || std::from_chars(off->data(), off->data() + off->size(), offset).ec != std::errc())
      return fail("missing or invalid offset");
    if (layout.appended_end == 0) return fail("no <AppendedData> section");
    const std::size_t available = layout.appended_end - layout.appended_begin;
    if (offset >= available) return fail("offset " + *off + " lies beyond the appended data");
    const std::size_t begin = layout.appended_begin + offset;
    if (layout.appended_raw) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(layout.file.data()) + begin;
      if (!extract_payload(p, layout.appended_end - begin, layout, want, &payload, &data, &why))
        return fail(why);
    } else {
      // A base64 array runs up to the next array's offset.
      std::size_t end = layout.appended_end;
      const auto next =
          std::upper_bound(layout.appended_offsets.begin(), layout.appended_offsets.end(), offset);
      if (next != layout.appended_offsets.end() && *next < available)
        end = layout.appended_begin + *next;
      if (!base64_decode(layout.file.data() + begin, layout.file.data() + end, &decoded))
        return fail("invalid base64 data");
      if (!extract_payload(decoded.data(), decoded.size(), layout, want, &payload, &data, &why))
        return fail(why);
    }
  } else {
    return fail("unsupported format '" + fmt + "'");
  }
  convert(data, t, size, count, layout.big_endian, out);
  return true;
}

}  // namespace

bool read_data_array(const XmlDocument& doc, std::size_t element, const VtuLayout& layout,
                     std::size_t count, int components, std::vector<double>* out,
                     std::string* error) {
  return read_array(doc, element, layout, count, components, out, error);
}

bool read_data_array(const XmlDocument& doc, std::size_t element, const VtuLayout& layout,
                     std::size_t count, int components, std::vector<std::int64_t>* out,
                     std::string* error) {
  return read_array(doc, element, layout, count, components, out, error);
}

}  // namespace vorohex::io::detail
