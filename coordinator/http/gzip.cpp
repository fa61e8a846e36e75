#include "coordinator/http/gzip.h"

#include <stdexcept>

#include <zlib.h>

namespace tessera {

std::string gzip(std::string_view bytes) {
  z_stream z{};
  // 15 bits of window, +16: a gzip header and trailer rather than zlib's.
  if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("gzip: deflateInit2 failed");
  std::string out(deflateBound(&z, static_cast<uLong>(bytes.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error("gzip: deflate did not finish");
  return out;
}

bool accepts_gzip(std::string_view accept_encoding) {
  // Tokens separated by commas, each maybe with ";q=..."; only an explicit q=0 refuses.
  std::size_t start = 0;
  while (start <= accept_encoding.size()) {
    const std::size_t comma = accept_encoding.find(',', start);
    std::string_view item = accept_encoding.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    if (item.starts_with("gzip")) {
      const std::size_t q = item.find("q=");
      return q == std::string_view::npos ||
             item.substr(q + 2).find_first_not_of("0.") != std::string_view::npos;
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return false;
}

}  // namespace tessera
