#include "common/protocol/handshake.h"

#include <array>
#include <cstdint>
#include <random>

#include "common/protocol/sha256.h"

namespace tessera {

std::string make_nonce() {
  std::random_device entropy;  // /dev/urandom with libstdc++ on Linux
  std::array<std::uint8_t, 32> bytes;
  for (auto& b : bytes) b = static_cast<std::uint8_t>(entropy());
  return to_hex(bytes.data(), bytes.size());
}

std::string worker_proof(const std::string& secret, const std::string& coordinator_nonce,
                         const std::string& worker_nonce) {
  return to_hex(hmac_sha256(secret, "tessera-worker|" + std::to_string(kProtocolVersion) + "|" +
                                        coordinator_nonce + "|" + worker_nonce));
}

std::string coordinator_proof(const std::string& secret, const std::string& coordinator_nonce,
                              const std::string& worker_nonce) {
  return to_hex(hmac_sha256(secret, "tessera-coordinator|" + std::to_string(kProtocolVersion) +
                                        "|" + worker_nonce + "|" + coordinator_nonce));
}

}  // namespace tessera
