#include "core/text.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace torte {

namespace {

// Quoted text escapes backslashes and quotes too, so the quote cannot be read wrongly; library messages keep
// theirs as they are.
void append_escaped(std::string& out, unsigned char c, bool quoting) {
  switch (c) {
    case '\t': out += "\\t"; return;
    case '\r': out += "\\r"; return;
    case '\n': out += "\\n"; return;
    case '\\': out += quoting ? "\\\\" : "\\"; return;
    case '\'': out += quoting ? "\\'" : "'"; return;
    default: break;
  }
  if (c < 0x20 || c >= 0x7f) {  // control bytes; bytes of invalid UTF-8
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\x%02x", c);
    out += buf;
  } else {
    out += char(c);
  }
}

// Length of the valid UTF-8 sequence starting at s[i] (2 to 4 bytes), or 0.
size_t utf8_length(std::string_view s, size_t i) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  const size_t n = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return 0;
  return n;
}

// Appends s (escaping control bytes and invalid UTF-8; valid UTF-8 passes) up to `max_chars` characters;
// returns the bytes consumed.
size_t append_text(std::string& out, std::string_view s, size_t max_chars, bool quoting) {
  size_t i = 0, chars = 0;
  while (i < s.size() && chars < max_chars) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x80) {
      if (const size_t n = utf8_length(s, i)) {
        out.append(s.substr(i, n));
        i += n;
        ++chars;
        continue;
      }
    }
    append_escaped(out, c, quoting);
    ++i;
    ++chars;
  }
  return i;
}

}  // namespace

std::string quote_text(std::string_view text, size_t max_chars) {
  std::string out = "'";
  const size_t used = append_text(out, text, max_chars, true);
  out += '\'';
  if (used < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::string escape_text(std::string_view text, size_t max_chars) {
  std::string out;
  if (append_text(out, text, max_chars, false) < text.size()) out += "...";
  return out;
}

std::string one_line_message(std::string_view text, std::string_view fallback, size_t max_chars) {
  std::vector<std::string_view> lines;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t' || line.front() == '\r'))
      line.remove_prefix(1);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r')) line.remove_suffix(1);
    if (line.empty()) continue;
    bool seen = false;
    for (std::string_view l : lines) seen |= l == line;
    if (!seen) lines.push_back(line);
  }
  std::string out;
  for (std::string_view line : lines) {
    if (!out.empty()) out += "; ";
    append_text(out, line, line.size(), false);
  }
  if (out.empty()) return std::string(fallback);
  if (out.size() > max_chars) {
    out.resize(max_chars);
    out += "...";
  }
  return out;
}

std::string format_number(float v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(v));
  return buf;
}

std::string lower_extension(std::string_view path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace torte
