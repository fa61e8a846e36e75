#include "common/protocol/handshake.h"

#include <gtest/gtest.h>

#include "common/protocol/sha256.h"

namespace tessera {
namespace {

TEST(Handshake, NoncesAreFreshHex) {
  const std::string a = make_nonce(), b = make_nonce();
  EXPECT_EQ(a.size(), 64u);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
}

TEST(Handshake, ProofsNeedTheSecretAndBothNonces) {
  const std::string nc = make_nonce(), nw = make_nonce();
  const std::string proof = worker_proof("s3cret", nc, nw);
  EXPECT_TRUE(constant_time_equal(proof, worker_proof("s3cret", nc, nw)));
  EXPECT_FALSE(constant_time_equal(proof, worker_proof("wrong", nc, nw)));
  EXPECT_NE(proof, worker_proof("s3cret", make_nonce(), nw));
  EXPECT_NE(proof, worker_proof("s3cret", nc, make_nonce()));
  // The two directions never share a proof, so one cannot be replayed as the other.
  EXPECT_NE(proof, coordinator_proof("s3cret", nc, nw));
  EXPECT_EQ(proof.find("s3cret"), std::string::npos);
}

}  // namespace
}  // namespace tessera
