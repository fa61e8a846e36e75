// The versioned handshake and the challenge/response that proves both sides know the shared
// secret without sending it (docs/PROTOCOL.md):
//
//   worker -> hello {version, name, threads, nonce: Nw, cached}
//   coordinator -> challenge {version, nonce: Nc, auth: "hmac-sha256" | "none"}
//   worker -> auth {proof: HMAC(secret, "tessera-worker|1|Nc|Nw")}
//   coordinator -> welcome {proof: HMAC(secret, "tessera-coordinator|1|Nw|Nc"), ...} or reject
//
// Fresh random nonces on both sides make every proof single-use; the worker checks the
// coordinator's proof so that nobody without the secret can feed it scenes either.
#pragma once

#include <string>

namespace tessera {

constexpr int kProtocolVersion = 2;

// 32 random bytes from the system's entropy source, as hex.
std::string make_nonce();
std::string worker_proof(const std::string& secret, const std::string& coordinator_nonce,
                         const std::string& worker_nonce);
std::string coordinator_proof(const std::string& secret, const std::string& coordinator_nonce,
                              const std::string& worker_nonce);

}  // namespace tessera
