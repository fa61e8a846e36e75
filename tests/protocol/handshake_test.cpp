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
  // Known answers from Python's hmac: HMAC-SHA256("s3cret", "tessera-worker|2|c…c|w…w").
  const std::string c(64, 'c'), w(64, 'w');
  EXPECT_EQ(worker_proof("s3cret", c, w),
            "f3a8f04a1a8487dce69e676f4c97bafdb54d8c23c87b454a2a5c4c6a881d8abf");
  EXPECT_EQ(coordinator_proof("s3cret", c, w),
            "84ff150ee30f93920f2a5e83b878cac6dab1f6932c3617fdcac3c533db13064e");
  const std::string nc = make_nonce(), nw = make_nonce();
  const std::string proof = worker_proof("s3cret", nc, nw);
  EXPECT_FALSE(constant_time_equal(proof, worker_proof("wrong", nc, nw)));
  EXPECT_NE(proof, worker_proof("s3cret", make_nonce(), nw));
  EXPECT_NE(proof, worker_proof("s3cret", nc, make_nonce()));
  // The two directions never share a proof, so one cannot be replayed as the other.
  EXPECT_NE(proof, coordinator_proof("s3cret", nc, nw));
  EXPECT_EQ(proof.find("s3cret"), std::string::npos);
}

}  // namespace
}  // namespace tessera
