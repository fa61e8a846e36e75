// Integers read from JSON that another process wrote. nlohmann's get<T>() converts unchecked:
// a float such as 1e37 cast to an integer is undefined behaviour (fuzz_worker_frames found a
// worker's result with one), and a wide integer is cut to T's bits. Every integer a peer or a
// request sends is read through json_integer.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

namespace tessera {

// The value when `v` is a JSON integer (not a float) within T's range, else nothing.
template <typename T>
std::optional<T> json_integer(const nlohmann::json& v) {
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (std::in_range<T>(u)) return static_cast<T>(u);
  } else if (v.is_number_integer()) {
    const auto i = v.get<std::int64_t>();
    if (std::in_range<T>(i)) return static_cast<T>(i);
  }
  return std::nullopt;
}

}  // namespace tessera
