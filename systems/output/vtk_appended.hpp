// The pieces of a VTK XML file with raw appended binary data: the byte order, the type names and the
// appended block built while the DataArray elements are written (vtk_frames.cpp, wall_surfaces.cpp).
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace gf::vtk {

// The data are written in the machine's own byte order and the header says which, so no
// per-value swapping is needed and readers on either kind of machine convert if they must.
inline constexpr const char* kByteOrder =
    std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

template <class T>
constexpr const char* vtk_type();
template <>
constexpr const char* vtk_type<double>() { return "Float64"; }
template <>
constexpr const char* vtk_type<std::int64_t>() { return "Int64"; }
template <>
constexpr const char* vtk_type<std::int32_t>() { return "Int32"; }
template <>
constexpr const char* vtk_type<std::uint8_t>() { return "UInt8"; }

// Shortest text that reads back as the same double, so .pvd times are exact.
inline std::string shortest(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

// Collects the appended binary block while emitting the matching DataArray elements. Each
// array's block is a UInt64 byte count then the values; `offset` counts from the byte after
// the '_' that opens the appended data.
class AppendedArrays {
 public:
  // `get(i, c)` gives component c of tuple i.
  template <class T, class Get>
  void add(std::string& xml, std::string_view indent, std::string_view name, int components,
           std::size_t tuples, Get&& get) {
    xml += indent;
    xml += "<DataArray type=\"";
    xml += vtk_type<T>();
    xml += "\" Name=\"";
    xml += name;
    xml += "\" NumberOfComponents=\"";
    xml += std::to_string(components);
    xml += "\" format=\"appended\" offset=\"";
    xml += std::to_string(blob_.size());
    xml += "\"/>\n";

    const auto ncomp = static_cast<std::size_t>(components);
    const std::uint64_t nbytes = tuples * ncomp * sizeof(T);
    const std::size_t start = blob_.size();
    // One resize and memcpy per value rather than string appends: frames of millions of
    // grains are written during the run, and this loop is their whole cost.
    blob_.resize(start + sizeof nbytes + nbytes);
    char* p = blob_.data() + start;
    std::memcpy(p, &nbytes, sizeof nbytes);
    p += sizeof nbytes;
    for (std::size_t i = 0; i < tuples; ++i)
      for (std::size_t c = 0; c < ncomp; ++c) {
        const T v = get(i, c);
        std::memcpy(p, &v, sizeof v);
        p += sizeof v;
      }
  }
  const std::string& blob() const { return blob_; }

 private:
  std::string blob_;
};

}  // namespace gf::vtk
