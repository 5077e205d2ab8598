#include "io/detail/base64.h"

#include <array>

namespace vorohex::io::detail {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// 0..63 for alphabet characters, 64 for whitespace, 65 for '=', 66 otherwise.
constexpr std::array<std::uint8_t, 256> make_decode_table() {
  std::array<std::uint8_t, 256> t{};
  for (auto& v : t) v = 66;
  for (int i = 0; i < 64; ++i)
    t[static_cast<unsigned char>(kAlphabet[i])] = static_cast<std::uint8_t>(i);
  t[' '] = t['\n'] = t['\r'] = t['\t'] = 64;
  t['='] = 65;
  return t;
}
constexpr std::array<std::uint8_t, 256> kDecode = make_decode_table();

}  // namespace

char* base64_encode(const std::uint8_t* in, std::size_t n, char* out) {
  std::size_t i = 0;
  for (; i + 3 <= n; i += 3) {
    const std::uint32_t v =
        (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8) | in[i + 2];
    out[0] = kAlphabet[v >> 18];
    out[1] = kAlphabet[(v >> 12) & 63];
    out[2] = kAlphabet[(v >> 6) & 63];
    out[3] = kAlphabet[v & 63];
    out += 4;
  }
  const std::size_t rest = n - i;
  if (rest) {
    const std::uint32_t v =
        (std::uint32_t(in[i]) << 16) | (rest == 2 ? std::uint32_t(in[i + 1]) << 8 : 0u);
    out[0] = kAlphabet[v >> 18];
    out[1] = kAlphabet[(v >> 12) & 63];
    out[2] = rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out[3] = '=';
    out += 4;
  }
  return out;
}

bool base64_decode(const char* begin, const char* end, std::vector<std::uint8_t>* out) {
  out->reserve(out->size() + static_cast<std::size_t>(end - begin) / 4 * 3 + 3);
  std::uint32_t quantum = 0;
  int have = 0;     // sextets collected in the current quantum
  int padding = 0;  // '=' seen in the current quantum
  for (const char* p = begin; p != end; ++p) {
    const std::uint8_t c = kDecode[static_cast<unsigned char>(*p)];
    if (c == 64) continue;
    if (c == 66) return false;
    if (c == 65) {
      // Padding completes a quantum of 2 or 3 sextets.
      if (have + padding < 2) return false;
      ++padding;
    } else {
      if (padding) return false;  // data after '=' inside one quantum
      quantum = (quantum << 6) | c;
      ++have;
    }
    if (have + padding == 4) {
      if (padding == 0) {
        out->push_back(static_cast<std::uint8_t>(quantum >> 16));
        out->push_back(static_cast<std::uint8_t>(quantum >> 8));
        out->push_back(static_cast<std::uint8_t>(quantum));
      } else if (padding == 1) {
        quantum >>= 2;  // 3 sextets = 18 bits hold 2 bytes
        out->push_back(static_cast<std::uint8_t>(quantum >> 8));
        out->push_back(static_cast<std::uint8_t>(quantum));
      } else if (padding == 2) {
        quantum >>= 4;  // 2 sextets = 12 bits hold 1 byte
        out->push_back(static_cast<std::uint8_t>(quantum));
      } else {
        return false;
      }
      quantum = 0;
      have = padding = 0;
    }
  }
  // Unpadded tails are tolerated (2 or 3 sextets), a single sextet is not.
  if (padding) return false;
  if (have == 1) return false;
  if (have == 2) out->push_back(static_cast<std::uint8_t>(quantum >> 4));
  if (have == 3) {
    quantum >>= 2;
    out->push_back(static_cast<std::uint8_t>(quantum >> 8));
    out->push_back(static_cast<std::uint8_t>(quantum));
  }
  return true;
}

}  // namespace vorohex::io::detail
