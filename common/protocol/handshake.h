// The versioned handshake and the challenge/response that proves both sides know the shared
// secret without sending it (docs/PROTOCOL.md):
//
//   worker -> hello {version, name, threads, nonce: Nw, cached}
//   coordinator -> challenge {version, nonce: Nc, auth: "hmac-sha256" | "none"}
//   worker -> auth {proof: HMAC(secret, "tessera-worker|V|Nc|Nw")}
//   coordinator -> welcome {worker: id, proof: HMAC(secret, "tessera-coordinator|V|Nw|Nc")}
//                  or reject {reason}
//
// V is kProtocolVersion. Fresh random nonces on both sides make every proof single-use. A
// worker given a secret checks the coordinator's proof and refuses auth "none", so that nobody
// without the secret can feed it scenes either (worker/session/worker_session.cpp).
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
