// A stable small integer per C++ type, used to key components and resources without strings.
#pragma once

#include <atomic>
#include <cstddef>

namespace gf {

namespace detail {
inline std::size_t next_type_id() {
  static std::atomic<std::size_t> counter{0};
  return counter++;
}
}  // namespace detail

template <class T>
std::size_t type_id() {
  static const std::size_t id = detail::next_type_id();
  return id;
}

}  // namespace gf
