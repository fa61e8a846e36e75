// The places a port keeps for peers that have not authenticated yet (strangers): at most
// `total` in all and `per_address` from any one address, so that one host cannot take every
// place and keep genuine workers out while it keeps reconnecting (docs/SECURITY.md). An IPv6
// peer is counted by its /64 network, which one host may hold whole. Single-threaded, like the
// io thread.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <boost/asio/ip/address.hpp>

namespace tessera {

class StrangerSlots {
  struct Counts {
    std::size_t total = 0;
    std::map<boost::asio::ip::address, std::size_t> by_address;
  };

 public:
  StrangerSlots(std::size_t total, std::size_t per_address)
      : max_total_(total), max_per_address_(per_address) {}

  // One stranger's place, given back when the place is destroyed or released. It may outlive
  // the StrangerSlots that gave it (a connection closing after its listener).
  class Place {
   public:
    Place(Place&& other) noexcept : counts_(std::move(other.counts_)), address_(other.address_) {}
    Place& operator=(Place&& other) noexcept {
      if (this != &other) {
        release();
        counts_ = std::move(other.counts_);
        address_ = other.address_;
      }
      return *this;
    }
    Place(const Place&) = delete;
    Place& operator=(const Place&) = delete;
    ~Place() { release(); }
    void release() {
      if (!counts_) return;
      --counts_->total;
      if (--counts_->by_address[address_] == 0) counts_->by_address.erase(address_);
      counts_.reset();
    }

   private:
    friend class StrangerSlots;
    Place(std::shared_ptr<Counts> counts, boost::asio::ip::address address)
        : counts_(std::move(counts)), address_(address) {}
    std::shared_ptr<Counts> counts_;
    boost::asio::ip::address address_;
  };

  // A place for a peer from `address`, or nothing when the port or that address has none
  // left; then `refusal` says which ("64 unauthenticated connections open", "8 from ADDR").
  std::optional<Place> enter(const boost::asio::ip::address& address, std::string& refusal) {
    const boost::asio::ip::address key = counted_as(address);
    if (counts_->total >= max_total_) {
      refusal = std::to_string(counts_->total) + " unauthenticated connections open";
      return std::nullopt;
    }
    std::size_t& from_address = counts_->by_address[key];
    if (from_address >= max_per_address_) {
      refusal = std::to_string(from_address) + " unauthenticated connections open from " +
                key.to_string();
      return std::nullopt;
    }
    ++from_address;
    ++counts_->total;
    return Place(counts_, key);
  }

  std::size_t held() const { return counts_->total; }
  std::size_t held_by(const boost::asio::ip::address& address) const {
    const auto it = counts_->by_address.find(counted_as(address));
    return it == counts_->by_address.end() ? 0 : it->second;
  }

  // The address a peer counts as: its own, an IPv4-mapped one as IPv4, other IPv6 ones as
  // their /64 network.
  static boost::asio::ip::address counted_as(const boost::asio::ip::address& address) {
    if (!address.is_v6()) return address;
    const boost::asio::ip::address_v6 v6 = address.to_v6();
    if (v6.is_v4_mapped()) return boost::asio::ip::make_address_v4(boost::asio::ip::v4_mapped, v6);
    boost::asio::ip::address_v6::bytes_type bytes = v6.to_bytes();
    for (std::size_t i = 8; i < bytes.size(); ++i) bytes[i] = 0;
    return boost::asio::ip::address_v6(bytes);
  }

 private:
  std::size_t max_total_, max_per_address_;
  std::shared_ptr<Counts> counts_ = std::make_shared<Counts>();
};

}  // namespace tessera
