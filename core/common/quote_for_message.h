#pragma once
// Text from a file or a command line, quoted for an error message (the readers of drivers/carmen
// and formats/ name a bad field by its text).

#include <string>
#include <string_view>

namespace atlas {

// `text` in single quotes: at most 40 bytes (then "..."), non-printable bytes as \xNN.
std::string QuoteForMessage(std::string_view text);

}  // namespace atlas
