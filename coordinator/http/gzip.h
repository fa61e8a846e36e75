// gzip (RFC 1952) for HTTP bodies the browser inflates itself (Content-Encoding: gzip), with
// zlib: the page's tile deltas, which compress several times over.
#pragma once

#include <string>
#include <string_view>

namespace tessera {

// zlib's default level 6: on a 1920x1080 job's tile answers 1.12 times the final PNG's bytes
// where level 1 gives 1.66 (9: 1.02). It runs on the io thread, on at most kTilesAnswerBytes
// (256 KiB: a few milliseconds).
std::string gzip(std::string_view bytes);
// Whether an Accept-Encoding header value admits gzip (no q=0 for it).
bool accepts_gzip(std::string_view accept_encoding);

}  // namespace tessera
