// Singletons of a world (clock, gravity, pair tables, contact lists, geometry), keyed by type.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "engine/type_id.hpp"

namespace gf {

class Resources {
 public:
  template <class R, class... Args>
  R& emplace(Args&&... args) {
    auto holder = std::make_unique<Holder<R>>(std::forward<Args>(args)...);
    R& ref = holder->value;
    const std::size_t key = type_id<R>();
    if (key >= slots_.size()) slots_.resize(key + 1);
    slots_[key] = std::move(holder);
    return ref;
  }
  template <class R>
  R* find() {
    const std::size_t key = type_id<R>();
    if (key >= slots_.size() || !slots_[key]) return nullptr;
    return &static_cast<Holder<R>&>(*slots_[key]).value;
  }
  template <class R>
  R& get() {
    if (R* r = find<R>()) return *r;
    throw std::logic_error(std::string("resource missing from world: ") + typeid(R).name());
  }
  template <class R>
  const R* find() const {
    return const_cast<Resources*>(this)->find<R>();
  }
  template <class R>
  const R& get() const {
    return const_cast<Resources*>(this)->get<R>();
  }

 private:
  struct Base {
    virtual ~Base() = default;
  };
  template <class R>
  struct Holder final : Base {
    template <class... Args>
    explicit Holder(Args&&... args) : value(std::forward<Args>(args)...) {}
    R value;
  };
  std::vector<std::unique_ptr<Base>> slots_;
};

}  // namespace gf
