// The tables of a world, keyed by type: grains, fluid nodes, and the bodies and members of
// composite grains as they arrive. Each is an archetype of its own (structure of arrays) whose
// owned rows come first; rows after them are ghosts, copies another domain owns, which kernels
// read but never write. A table type declares its name and row counts:
//   static constexpr std::string_view kName;  std::size_t owned_rows() const;
//   std::size_t rows() const (owned + ghosts);  std::size_t bytes();
#pragma once

#include <concepts>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "engine/type_id.hpp"

namespace gf {

template <class T>
concept TableType = requires(T t, const T c) {
  { T::kName } -> std::convertible_to<std::string_view>;
  { c.owned_rows() } -> std::convertible_to<std::size_t>;
  { c.rows() } -> std::convertible_to<std::size_t>;
  { t.bytes() } -> std::convertible_to<std::size_t>;
};

struct TableInfo {
  std::string_view name;
  std::size_t owned = 0, rows = 0, bytes = 0;
};

class Tables {
 public:
  template <TableType T>
  T& add() {
    if (T* t = find<T>()) return *t;
    auto m = std::make_unique<Model<T>>();
    m->key = type_id<T>();
    T& ref = m->value;
    tables_.push_back(std::move(m));
    return ref;
  }
  template <TableType T>
  T* find() {
    for (auto& t : tables_)
      if (t->key == type_id<T>()) return &static_cast<Model<T>&>(*t).value;
    return nullptr;
  }
  template <TableType T>
  T& get() {
    if (T* t = find<T>()) return *t;
    throw std::logic_error("table missing from world: " + std::string(T::kName));
  }
  // Every table in the order added, for reports (`grainflow check`, memory estimates).
  std::vector<TableInfo> info() {
    std::vector<TableInfo> out;
    for (auto& t : tables_) out.push_back(t->info());
    return out;
  }

 private:
  struct Base {
    virtual ~Base() = default;
    virtual TableInfo info() = 0;
    std::size_t key = 0;
  };
  template <class T>
  struct Model final : Base {
    T value;
    TableInfo info() override { return {T::kName, value.owned_rows(), value.rows(), value.bytes()}; }
  };
  std::vector<std::unique_ptr<Base>> tables_;
};

}  // namespace gf
