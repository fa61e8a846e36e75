// SHA-256 (FIPS 180-4) and HMAC-SHA256 (RFC 2104), for worker authentication and for content
// hashes of scene bundles, from OpenSSL's libcrypto: no cryptography of our own. The
// known-answer tests in tests/protocol pin the wrappers down.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace tessera {

using Sha256Digest = std::array<std::uint8_t, 32>;

Sha256Digest sha256(std::string_view data);
Sha256Digest hmac_sha256(std::string_view key, std::string_view message);
std::string to_hex(const std::uint8_t* data, std::size_t size);
inline std::string to_hex(const Sha256Digest& d) { return to_hex(d.data(), d.size()); }

// Compares without an early exit (CRYPTO_memcmp), so timing does not reveal how much of a
// proof was right.
bool constant_time_equal(std::string_view a, std::string_view b);

}  // namespace tessera
