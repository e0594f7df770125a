// Text from the user (or from a file) put into a message.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace gf {

// Text from the user for a message, at most `max` characters ("..." marks the cut): a 100 kB value
// must not become a 100 kB line; control characters are written \xNN. clipped() as is, quoted() in
// single quotes.
std::string clipped(std::string_view s, std::size_t max = 60);
// The text with control characters other than line ends written \xNN: every message of a refusal
// passes through it, so no file content can cut a message short or reach the terminal as a command.
std::string printable(std::string_view s);
std::string quoted(std::string_view s, std::size_t max = 60);

}  // namespace gf
