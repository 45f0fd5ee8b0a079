// The report's tables: built once as cells, printed for the terminal, Markdown and HTML.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

struct TextTable {
  std::vector<std::string> headers;
  std::vector<std::vector<std::string>> rows;
};

// Columns padded to their widest cell, the first left-aligned, the others right-aligned.
std::string as_text(const TextTable& table);
std::string as_markdown(const TextTable& table);
// A <table> with every cell escaped (html_escape).
std::string as_html(const TextTable& table);

// The text with '<', '>' and '&' escaped.
std::string html_escape(std::string_view text);

}  // namespace saagen::report
