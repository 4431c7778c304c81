// Text from files and libraries made safe for one-line error messages: control bytes escaped, lines joined,
// length capped; and the extension of a file name.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace torte {

/// `text` in single quotes with control bytes, bytes >= 0x7f, quotes and backslashes escaped (\x00, \t, \', \\)
/// and at most `max_chars` characters of it shown (then "..." and the length in bytes), so a message quoting a
/// corrupt file's bytes stays one printable line.
std::string quote_text(std::string_view text, size_t max_chars = 40);

/// `text` with control bytes and invalid UTF-8 escaped as in quote_text but unquoted and quotes left as they
/// are, capped at `max_chars` (then "..."): for file names in messages ("<file>: line 3: ...").
std::string escape_text(std::string_view text, size_t max_chars = 200);

/// A library's message (OpenImageIO's may span lines and repeat a line) as one line: lines trimmed and joined
/// with "; ", repeated lines dropped, other control bytes escaped, capped at `max_chars`. `fallback` when empty.
std::string one_line_message(std::string_view text, std::string_view fallback = "unknown error",
                             size_t max_chars = 300);

/// A float for a message: "%g", and "nan" for every NaN (printf writes "-nan" for some).
std::string format_number(float v);

/// The file name's extension in lower case, with its dot (".exr"); empty when it has none (std::filesystem's
/// rule: "dir/.hidden" has none). What picks a file's format by its name.
std::string lower_extension(std::string_view path);

}  // namespace torte
