// docs/PROTOCOL.md against the code: the version it states and the proof strings its handshake
// shows must be the ones common/protocol/handshake.cpp uses, or a reader implementing a worker
// from the page is refused by every coordinator (issue 23, §6).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "common/protocol/handshake.h"
#include "common/protocol/sha256.h"

namespace tessera {
namespace {

std::string protocol_page() {
  std::ifstream in(std::string(TESSERA_SOURCE_DIR) + "/docs/PROTOCOL.md");
  EXPECT_TRUE(in) << "cannot read docs/PROTOCOL.md";
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::smatch> all_matches(const std::string& text, const std::regex& pattern) {
  return {std::sregex_iterator(text.begin(), text.end(), pattern), std::sregex_iterator()};
}

TEST(ProtocolDoc, StatesTheCodesVersion) {
  const std::string page = protocol_page();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(page, m, std::regex(R"(\nVersion (\d+)\b)")));
  EXPECT_EQ(std::stoi(m[1]), kProtocolVersion);
  // The hello and the challenge of the handshake's sketch carry it too.
  const auto versions = all_matches(page, std::regex(R"(\{version: (\d+),)"));
  ASSERT_EQ(versions.size(), 2u);
  for (const auto& v : versions) EXPECT_EQ(std::stoi(v[1]), kProtocolVersion) << v[0];
}

// The page's proof templates, with concrete nonces, hashed here must give the code's proofs.
TEST(ProtocolDoc, ProofStringsAreTheCodes) {
  const std::string page = protocol_page();
  const auto proofs = all_matches(
      page,
      std::regex(R"re(HMAC-SHA256\(secret, "(tessera-[a-z]+)\|(\d+)\|(N[cw])\|(N[cw])"\))re"));
  ASSERT_EQ(proofs.size(), 2u);
  const std::string secret = "doc-secret", nc = make_nonce(), nw = make_nonce();
  for (const auto& p : proofs) {
    const auto nonce = [&](const std::string& name) { return name == "Nc" ? nc : nw; };
    const std::string message =
        p[1].str() + "|" + p[2].str() + "|" + nonce(p[3]) + "|" + nonce(p[4]);
    const std::string from_page = to_hex(hmac_sha256(secret, message));
    if (p[1] == "tessera-worker")
      EXPECT_EQ(from_page, worker_proof(secret, nc, nw)) << p[0];
    else
      EXPECT_EQ(from_page, coordinator_proof(secret, nc, nw)) << p[0];
  }
  EXPECT_NE(proofs[0][1], proofs[1][1]);  // one template per direction
}

}  // namespace
}  // namespace tessera
