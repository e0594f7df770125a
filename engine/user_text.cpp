#include "engine/user_text.hpp"

#include <algorithm>

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

std::string shown_path(std::string_view path, std::size_t max) {
  if (path.size() <= max) return escaped(path, false);
  return "..." + escaped(path.substr(path.size() - max), false);
}

std::string quoted(std::string_view s, std::size_t max) {
  // Built by appends: GCC 12 warns (-Wrestrict, a known false positive) on "'" + std::string.
  std::string out;
  out += '\'';
  out += clipped(s, max);
  out += '\'';
  return out;
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  return r;
}

// Optimal string alignment distance: insertions, deletions, substitutions and adjacent swaps ("dnesity") cost 1.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

// The closest candidate within edit distance 2, or "". Short words need a closer match: two edits turn any 2-letter
// key into any other, and "did you mean 'dt'?" for 'xy' would only mislead.
std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = 3;
  const std::string w = lower(word);
  for (const auto& c : candidates) {
    if (c == word) continue;
    const std::size_t d = edit_distance(w, lower(c));
    const bool close = d == 0 || (d <= 2 && 2 * d <= w.size());
    if (close && d < best_d) {
      best = c;
      best_d = d;
    }
  }
  return best;
}

}  // namespace gf
