// A Beast body whose bytes are shared, not owned: a response that sends a done job's encoded
// image (up to hundreds of MB at 7680x4320) refers to the bytes the job keeps instead of copying
// them on the io thread, and Beast writes them in chunks as the socket takes them. Assigning a
// std::string (every other response) moves it into a shared buffer of its own.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/optional.hpp>

namespace tessera {

struct SharedStringBody {
  class value_type {
   public:
    value_type& operator=(std::string text) {
      bytes_ = std::make_shared<const std::string>(std::move(text));
      return *this;
    }
    value_type& operator=(std::shared_ptr<const std::string> shared) {
      bytes_ = std::move(shared);
      return *this;
    }
    std::size_t size() const { return bytes_ ? bytes_->size() : 0; }
    const char* data() const { return bytes_ ? bytes_->data() : nullptr; }

   private:
    std::shared_ptr<const std::string> bytes_;
  };

  static std::uint64_t size(const value_type& body) { return body.size(); }

  // Hands Beast's serializer the bytes 64 KiB at a time.
  class writer {
   public:
    using const_buffers_type = boost::asio::const_buffer;
    template <bool isRequest, class Fields>
    writer(const boost::beast::http::header<isRequest, Fields>&, const value_type& body)
        : body_(body) {}
    void init(boost::beast::error_code& ec) { ec = {}; }
    boost::optional<std::pair<const_buffers_type, bool>> get(boost::beast::error_code& ec) {
      ec = {};
      const std::size_t total = body_.size();
      if (offset_ >= total) return boost::none;
      const std::size_t n = std::min<std::size_t>(kChunk, total - offset_);
      const_buffers_type chunk(body_.data() + offset_, n);
      offset_ += n;
      return std::make_pair(chunk, offset_ < total);
    }

   private:
    static constexpr std::size_t kChunk = 64 * 1024;
    const value_type& body_;
    std::size_t offset_ = 0;
  };
};

}  // namespace tessera
