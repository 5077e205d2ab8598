// Splits [0, n) into contiguous chunks run on std::threads (only when n is large).
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace vorohex::quality::detail {

// Number of chunks parallel_chunks will use for n items.
inline std::size_t num_chunks(std::size_t n, std::size_t min_per_chunk) {
  const std::size_t hw = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t by_size = min_per_chunk ? n / min_per_chunk : n;
  return std::max<std::size_t>(1, std::min<std::size_t>({hw, 8, by_size}));
}

// Calls fn(chunk, begin, end) for each chunk, chunk 0 on the calling thread.
template <class Fn>
void parallel_chunks(std::size_t n, std::size_t min_per_chunk, Fn&& fn) {
  const std::size_t chunks = num_chunks(n, min_per_chunk);
  const std::size_t size = (n + chunks - 1) / chunks;
  std::vector<std::thread> pool;
  for (std::size_t c = 1; c < chunks; ++c)
    pool.emplace_back(
        [&fn, c, size, n] { fn(c, std::min(n, c * size), std::min(n, (c + 1) * size)); });
  fn(std::size_t{0}, std::size_t{0}, std::min(n, size));
  for (auto& t : pool) t.join();
}

}  // namespace vorohex::quality::detail
