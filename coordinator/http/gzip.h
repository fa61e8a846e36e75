// gzip (RFC 1952) for HTTP bodies the browser inflates itself (Content-Encoding: gzip), with
// zlib: the page's tile deltas, which compress several times over.
#pragma once

#include <string>
#include <string_view>

namespace tessera {

// Fast compression (level 1): it runs on the io thread, on at most kTilesAnswerBytes.
std::string gzip(std::string_view bytes);
// Whether an Accept-Encoding header value admits gzip (no q=0 for it).
bool accepts_gzip(std::string_view accept_encoding);

}  // namespace tessera
