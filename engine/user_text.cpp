#include "engine/user_text.hpp"

namespace gf {

namespace {

// A NUL would end the printed message, an escape sequence would reach the terminal.
std::string escaped(std::string_view s, bool keep_line_ends) {
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if ((u >= 0x20 && u != 0x7f) || (keep_line_ends && c == '\n')) {
      out += c;
      continue;
    }
    static const char hex[] = "0123456789abcdef";
    out += "\\x";
    out += hex[u >> 4];
    out += hex[u & 15];
  }
  return out;
}

}  // namespace

std::string printable(std::string_view s) { return escaped(s, true); }

std::string clipped(std::string_view s, std::size_t max) {
  std::string out = escaped(s.substr(0, max), false);
  if (s.size() > max) out += "...";
  return out;
}

std::string quoted(std::string_view s, std::size_t max) {
  // Built by appends: GCC 12 warns (-Wrestrict, a known false positive) on "'" + std::string.
  std::string out;
  out += '\'';
  out += clipped(s, max);
  out += '\'';
  return out;
}

}  // namespace gf
