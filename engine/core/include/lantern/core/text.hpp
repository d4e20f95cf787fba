// Input quoted in messages: one line whatever the input holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace lantern {

// `text` as it may appear inside a one-line message: printable ASCII and well-formed UTF-8
// kept, tab/newline/carriage return written \t \n \r, every other control character and
// every byte that is not part of well-formed UTF-8 written \xNN. Cut after `max_bytes` bytes
// of input (never inside a character), with "..." appended when cut.
std::string printable(std::string_view text, std::size_t max_bytes = 40);

// The length in bytes of the well-formed UTF-8 character at the start of `text`, or 0
// when it does not start with one (an invalid or truncated sequence, an overlong form, a
// surrogate). `code_point` receives its value.
std::size_t utf8_char(std::string_view text, std::uint32_t* code_point = nullptr);

} // namespace lantern
