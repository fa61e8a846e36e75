#include "common/protocol/tls.h"

#include <stdexcept>
#include <utility>

#include <openssl/ssl.h>
#include <openssl/x509v3.h>

namespace tessera {

namespace asio = boost::asio;
namespace ssl = asio::ssl;
using asio::ip::tcp;

namespace {

std::shared_ptr<ssl::context> tls12_context(ssl::context::method method) {
  auto context = std::make_shared<ssl::context>(method);
  SSL_CTX_set_min_proto_version(context->native_handle(), TLS1_2_VERSION);
  context->set_options(ssl::context::default_workarounds | ssl::context::no_compression);
  return context;
}

}  // namespace

std::shared_ptr<ssl::context> make_server_tls(const std::filesystem::path& cert,
                                              const std::filesystem::path& key) {
  // OpenSSL's own message for a missing file is only "asio.ssl error".
  for (const auto& [flag, file] : {std::pair{"--tls-cert", cert}, std::pair{"--tls-key", key}})
    if (!std::filesystem::is_regular_file(file))
      throw std::runtime_error(std::string("cannot load ") + flag + " " + file.string() +
                               ": no such file");
  auto context = tls12_context(ssl::context::tls_server);
  boost::system::error_code ec;
  context->use_certificate_chain_file(cert.string(), ec);
  if (ec) throw std::runtime_error("cannot load --tls-cert " + cert.string() + ": " + ec.message());
  context->use_private_key_file(key.string(), ssl::context::pem, ec);
  if (ec) throw std::runtime_error("cannot load --tls-key " + key.string() + ": " + ec.message());
  if (SSL_CTX_check_private_key(context->native_handle()) != 1)
    throw std::runtime_error("--tls-key " + key.string() + " does not match --tls-cert " +
                             cert.string());
  return context;
}

std::shared_ptr<ssl::context> make_client_tls(const ClientTlsOptions& options) {
  auto context = tls12_context(ssl::context::tls_client);
  if (options.insecure) {
    context->set_verify_mode(ssl::verify_none);
    return context;
  }
  boost::system::error_code ec;
  if (options.ca)
    context->load_verify_file(options.ca->string(), ec);
  else
    context->set_default_verify_paths(ec);
  if (ec)
    throw std::runtime_error("cannot load --tls-ca " +
                             (options.ca ? options.ca->string() : "(system store)") + ": " +
                             ec.message());
  context->set_verify_mode(ssl::verify_peer);
  return context;
}

FrameStream::FrameStream(tcp::socket socket) : plain_(std::move(socket)) {}

FrameStream::FrameStream(tcp::socket socket, std::shared_ptr<ssl::context> tls)
    : context_(std::move(tls)), tls_(std::make_unique<Tls>(std::move(socket), *context_)) {}

FrameStream::FrameStream(tcp::socket socket, std::shared_ptr<ssl::context> tls,
                         const std::string& host)
    : FrameStream(std::move(socket), std::move(tls)) {
  client_ = true;
  expect_peer_name(tls_->native_handle(), host);
}

void expect_peer_name(SSL* ssl, const std::string& host) {
  // OpenSSL checks the name during the handshake: an address against the certificate's IP
  // entries, a name against its DNS entries (and is sent as SNI).
  X509_VERIFY_PARAM* param = SSL_get0_param(ssl);
  boost::system::error_code ec;
  asio::ip::make_address(host, ec);
  if (!ec) {
    X509_VERIFY_PARAM_set1_ip_asc(param, host.c_str());
  } else {
    X509_VERIFY_PARAM_set_hostflags(param, X509_CHECK_FLAG_NO_PARTIAL_WILDCARDS);
    X509_VERIFY_PARAM_set1_host(param, host.c_str(), 0);
    SSL_set_tlsext_host_name(ssl, host.c_str());
  }
}

}  // namespace tessera
