// The report's tables as text, Markdown and HTML (see text_table.hpp).
#include "text_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace saagen::report {

std::string as_text(const TextTable& table) {
  std::vector<std::size_t> widths;
  for (const std::string& h : table.headers) widths.push_back(h.size());
  for (const auto& row : table.rows)
    for (std::size_t c = 0; c < row.size() && c < widths.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  const auto line = [&](const std::vector<std::string>& cells) {
    std::string text;
    for (std::size_t c = 0; c < cells.size(); ++c)
      text += c == 0 ? fmt::format("{:<{}}", cells[c], widths[c]) : fmt::format("  {:>{}}", cells[c], widths[c]);
    return text + "\n";
  };
  std::string text = line(table.headers);
  for (const auto& row : table.rows) text += line(row);
  return text;
}

std::string as_markdown(const TextTable& table) {
  std::string text = "| " + fmt::format("{}", fmt::join(table.headers, " | ")) + " |\n|";
  for (std::size_t c = 0; c < table.headers.size(); ++c) text += "---|";
  text += "\n";
  for (const auto& row : table.rows) text += "| " + fmt::format("{}", fmt::join(row, " | ")) + " |\n";
  return text;
}

std::string as_html(const TextTable& table) {
  std::string text = "<table><tr>";
  for (const std::string& h : table.headers) text += "<th>" + html_escape(h) + "</th>";
  text += "</tr>\n";
  for (const auto& row : table.rows) {
    text += "<tr>";
    for (const std::string& cell : row) text += "<td>" + html_escape(cell) + "</td>";
    text += "</tr>\n";
  }
  return text + "</table>\n";
}

std::string html_escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

}  // namespace saagen::report
