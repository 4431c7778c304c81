// The machine-readable parts of docs/lua-api.md: one `### \`name...\`` section per callable, its signature line,
// `Keys of \`NAME\`:` tables (NAME is the KwArgs function string) and its ```lua examples. Read by
// test_lua_api_doc.cc, which checks them against the bindings and generates the LuaLS stubs from them.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace torte::test {

struct ApiKey {
  std::string key, type, fallback, range, description;
};
struct ApiKeyTable {
  std::string function;  // the KwArgs name, e.g. "torte.material.matte" or "grid:define faces"
  int line = 0;
  std::vector<ApiKey> keys;
};
struct ApiExample {
  int line = 0;  // of the opening fence
  bool run = true;  // false for ```lua norun
  std::string code;
};
struct ApiSection {
  std::string name;       // "torte.material.matte", "image:write", "torte.args"
  std::string signature;  // the first code span line under the heading, without the backticks
  std::string contract;   // the prose up to the first blank line after the signature
  int line = 0;
  std::vector<ApiKeyTable> tables;
  std::vector<ApiExample> examples;
};

// Throws std::runtime_error("lua-api.md:<line>: ...") on a malformed section, table or fence.
inline std::vector<ApiSection> parse_api_doc(const std::string& text) {
  std::vector<ApiSection> sections;
  std::vector<std::string> lines;
  for (size_t start = 0; start <= text.size();) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  auto fail = [](size_t i, const std::string& what) {
    throw std::runtime_error("lua-api.md:" + std::to_string(i + 1) + ": " + what);
  };
  auto trim = [](std::string s) {
    const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
  };
  auto cells = [&](const std::string& row, size_t i) {  // "| a | b |" -> {"a", "b"}; "\|" stays in a cell
    if (row.size() < 2 || row.front() != '|' || row.back() != '|') fail(i, "a table row must start and end with |");
    std::vector<std::string> out;
    std::string cell;
    for (size_t k = 1; k + 1 < row.size(); ++k) {
      if (row[k] == '\\' && row[k + 1] == '|') {
        cell += '|';
        ++k;
      } else if (row[k] == '|') {
        out.push_back(trim(cell));
        cell.clear();
      } else {
        cell += row[k];
      }
    }
    out.push_back(trim(cell));
    return out;
  };
  auto unquote = [](const std::string& s) {  // `x` -> x
    return s.size() >= 2 && s.front() == '`' && s.back() == '`' ? s.substr(1, s.size() - 2) : s;
  };
  const std::string kHeader = "| key | type | default | range | description |";
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.rfind("```", 0) == 0) {  // a fence: skip to its end, keeping lua examples
      const std::string info = trim(line.substr(3));
      size_t j = i + 1;
      std::string code;
      for (; j < lines.size() && lines[j].rfind("```", 0) != 0; ++j) code += lines[j] + "\n";
      if (j == lines.size()) fail(i, "a code block that is never closed");
      if (info == "lua" || info == "lua norun") {
        if (sections.empty()) fail(i, "a lua example before the first ### section");
        sections.back().examples.push_back({int(i + 1), info == "lua", code});
      }
      i = j;
      continue;
    }
    if (line.rfind("### ", 0) == 0) {
      const size_t a = line.find('`');
      if (a == std::string::npos) continue;  // a heading that names no callable
      const size_t b = line.find('`', a + 1);
      if (b == std::string::npos) fail(i, "an unclosed ` in a heading");
      const std::string span = line.substr(a + 1, b - a - 1);
      ApiSection s;
      s.name = span.substr(0, span.find_first_of("{( "));
      s.line = int(i + 1);
      size_t j = i + 1;
      while (j < lines.size() && trim(lines[j]).empty()) ++j;
      if (j < lines.size() && lines[j].front() == '`') {
        const size_t e = lines[j].find('`', 1);
        s.signature = lines[j].substr(1, e == std::string::npos ? std::string::npos : e - 1);
        for (++j; j < lines.size() && !trim(lines[j]).empty() && lines[j].rfind("```", 0) != 0 &&
                  lines[j].rfind("Keys of ", 0) != 0;
             ++j)
          s.contract += (s.contract.empty() ? "" : " ") + trim(lines[j]);
      }
      sections.push_back(std::move(s));
      continue;
    }
    if (line.rfind("Keys of `", 0) == 0) {
      const size_t e = line.find('`', 9);
      if (e == std::string::npos || line.substr(e) != "`:") fail(i, "expected Keys of `NAME`:");
      if (sections.empty()) fail(i, "a key table before the first ### section");
      ApiKeyTable t;
      t.function = line.substr(9, e - 9);
      t.line = int(i + 1);
      size_t j = i + 1;
      while (j < lines.size() && trim(lines[j]).empty()) ++j;
      if (j + 1 >= lines.size() || trim(lines[j]) != kHeader)
        fail(j, "a key table must start with the header " + kHeader);
      for (j += 2; j < lines.size() && lines[j].rfind("|", 0) == 0; ++j) {
        const std::vector<std::string> c = cells(trim(lines[j]), j);
        if (c.size() != 5) fail(j, "a key row needs 5 cells, has " + std::to_string(c.size()));
        if (c[0].size() < 3 || c[0].front() != '`' || c[0].back() != '`') fail(j, "the key must be in backticks");
        t.keys.push_back({unquote(c[0]), c[1], unquote(c[2]), c[3], c[4]});
      }
      if (t.keys.empty()) fail(i, "a key table without rows");
      sections.back().tables.push_back(std::move(t));
      i = j - 1;
    }
  }
  return sections;
}

}  // namespace torte::test
