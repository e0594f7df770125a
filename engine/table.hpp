// A table is an archetype: rows are entities, each component a group of named columns.
// Core components are members of the concrete table; systems may attach further components
// (contact history against walls, say) that are resized and permuted with every other column.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "engine/column.hpp"
#include "engine/type_id.hpp"

namespace gf {

// Applies f to every column of a component: a struct exposing columns() as a tuple of references,
// or, for components whose column count is known only at run time, visit_columns(f).
template <class Component, class F>
void for_each_column(Component& c, F&& f) {
  if constexpr (requires { c.columns(); })
    std::apply([&](auto&... col) { (f(col), ...); }, c.columns());
  else
    c.visit_columns(f);
}

// An untyped view of one column, for code that moves whole tables as bytes (checkpoints).
struct RawColumn {
  void* data;
  std::size_t elem_size;
  std::size_t size;
};

class ExtraComponents {
 public:
  template <class C>
  C& attach(std::size_t n) {
    const std::size_t key = type_id<C>();
    for (auto& e : extras_)
      if (e->key == key) return static_cast<Model<C>&>(*e).value;
    auto m = std::make_unique<Model<C>>();
    m->key = key;
    for_each_column(m->value, [n](auto& col) { col.resize(n); });
    C& ref = m->value;
    extras_.push_back(std::move(m));
    return ref;
  }
  template <class C>
  C* find() {
    const std::size_t key = type_id<C>();
    for (auto& e : extras_)
      if (e->key == key) return &static_cast<Model<C>&>(*e).value;
    return nullptr;
  }
  template <class C>
  C& get() {
    if (C* c = find<C>()) return *c;
    throw std::logic_error("component not attached to table");
  }
  void resize(std::size_t n) {
    for (auto& e : extras_) e->resize(n);
  }
  void permute(std::span<const std::uint32_t> perm) {
    for (auto& e : extras_) e->permute(perm);
  }
  std::size_t bytes() const {
    std::size_t b = 0;
    for (auto& e : extras_) b += e->bytes();
    return b;
  }
  // Every attached column in attach order, then column order within each component.
  std::vector<RawColumn> raw_columns() {
    std::vector<RawColumn> out;
    for (auto& e : extras_) e->raw(out);
    return out;
  }

 private:
  struct Base {
    virtual ~Base() = default;
    virtual void resize(std::size_t n) = 0;
    virtual void permute(std::span<const std::uint32_t> perm) = 0;
    virtual std::size_t bytes() const = 0;
    virtual void raw(std::vector<RawColumn>& out) = 0;
    std::size_t key = 0;
  };
  template <class C>
  struct Model final : Base {
    C value;
    void resize(std::size_t n) override {
      for_each_column(value, [n](auto& col) { col.resize(n); });
    }
    void permute(std::span<const std::uint32_t> perm) override {
      for_each_column(value, [perm](auto& col) { col.permute(perm); });
    }
    std::size_t bytes() const override {
      std::size_t b = 0;
      for_each_column(const_cast<C&>(value), [&b](auto& col) { b += col.bytes(); });
      return b;
    }
    void raw(std::vector<RawColumn>& out) override {
      for_each_column(value, [&out](auto& col) { out.push_back({col.data(), sizeof(*col.data()), col.size()}); });
    }
  };
  std::vector<std::unique_ptr<Base>> extras_;
};

}  // namespace gf
