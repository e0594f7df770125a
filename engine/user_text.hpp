// Text from the user (or from a file) put into a message.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gf {

// Text from the user for a message, at most `max` characters ("..." marks the cut): a 100 kB value
// must not become a 100 kB line; control characters are written \xNN. clipped() as is, quoted() in
// single quotes.
std::string clipped(std::string_view s, std::size_t max = 60);
// The text with control characters other than line ends written \xNN: every message of a refusal
// passes through it, so no file content can cut a message short or reach the terminal as a command.
std::string printable(std::string_view s);
std::string quoted(std::string_view s, std::size_t max = 60);
// A path for a message, its last `max` characters when longer ("..." marks the cut): the file's name is
// the part a reader needs, and a 2 MB path typed into a scene must not become a 2 MB line.
std::string shown_path(std::string_view path, std::size_t max = 160);

// ASCII lower case.
std::string lower(std::string_view s);
// Optimal string alignment distance: insertions, deletions, substitutions and adjacent swaps cost 1.
std::size_t edit_distance(std::string_view a, std::string_view b);
// The candidate closest to `word` (case ignored) within edit distance 2, or "": the "did you mean" of a
// mistyped key or option. Short words need a closer match (2 edits turn any 2-letter word into another).
std::string closest(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace gf
