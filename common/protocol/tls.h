// TLS for the worker link (issue 17 §3), through Boost.Asio's OpenSSL streams: the contexts the
// coordinator and the worker make from their flags, and FrameStream, the byte stream under a
// FrameConnection, which is a plain TCP socket or TLS over one. No cryptography of our own.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>  // before Asio: Boost 1.74 uses std::exchange without it

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>

namespace tessera {

// The coordinator's: serves the certificate chain and key (PEM) with TLS 1.2 or later.
// Throws std::runtime_error naming the file that cannot be loaded.
std::shared_ptr<boost::asio::ssl::context> make_server_tls(const std::filesystem::path& cert,
                                                           const std::filesystem::path& key);

struct ClientTlsOptions {
  std::optional<std::filesystem::path> ca;  // trusted certificates; the system's when absent
  bool insecure = false;                    // no verification at all (--tls-insecure)
};

// The worker's: TLS 1.2 or later, the peer's chain verified against the CA (its host name is
// checked per connection, FrameStream).
std::shared_ptr<boost::asio::ssl::context> make_client_tls(const ClientTlsOptions& options);

// A client's TLS stream will check that the peer's certificate is `host`'s (a name or an
// address; a name is also sent as SNI). Call before the handshake.
void expect_peer_name(SSL* ssl, const std::string& host);

// A plain socket, or TLS over one; the TLS handshake is run by handshake() before any frame.
class FrameStream {
 public:
  using executor_type = boost::asio::ip::tcp::socket::executor_type;
  using Tls = boost::asio::ssl::stream<boost::asio::ip::tcp::socket>;

  // Plain TCP; implicit, since a plain socket is the usual stream.
  FrameStream(boost::asio::ip::tcp::socket socket);  // NOLINT(google-explicit-constructor)
  // The server's side of TLS.
  FrameStream(boost::asio::ip::tcp::socket socket, std::shared_ptr<boost::asio::ssl::context> tls);
  // The client's side: `host` (a name or an address) must match the peer's certificate unless
  // the context verifies nothing; it is also sent as SNI when it is a name.
  FrameStream(boost::asio::ip::tcp::socket socket, std::shared_ptr<boost::asio::ssl::context> tls,
              const std::string& host);

  executor_type get_executor() { return socket().get_executor(); }
  boost::asio::ip::tcp::socket& socket() { return tls_ ? tls_->next_layer() : *plain_; }
  bool tls() const { return tls_ != nullptr; }

  // Completes at once for a plain socket.
  template <class Handler>
  void handshake(Handler&& handler) {
    if (!tls_) return handler(boost::system::error_code());
    tls_->async_handshake(client_ ? Tls::client : Tls::server, std::forward<Handler>(handler));
  }
  template <class Buffers, class Handler>
  void async_read_some(const Buffers& buffers, Handler&& handler) {
    if (tls_) return tls_->async_read_some(buffers, std::forward<Handler>(handler));
    plain_->async_read_some(buffers, std::forward<Handler>(handler));
  }
  template <class Buffers, class Handler>
  void async_write_some(const Buffers& buffers, Handler&& handler) {
    if (tls_) return tls_->async_write_some(buffers, std::forward<Handler>(handler));
    plain_->async_write_some(buffers, std::forward<Handler>(handler));
  }

 private:
  std::shared_ptr<boost::asio::ssl::context> context_;  // outlives tls_
  std::unique_ptr<Tls> tls_;
  std::optional<boost::asio::ip::tcp::socket> plain_;
  bool client_ = false;
};

}  // namespace tessera
