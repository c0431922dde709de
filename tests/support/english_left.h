// Test support: the English words left in a page meant to be Russian (issue 20). The page's
// visible text is taken without its style sheet, markup, SVG <desc>/<title> (not shown) and
// the words of `allowed` (symbols, standards' and programs' names, file names); every other
// run of three or more Latin letters is reported with its context.
#pragma once

#include <algorithm>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace foglab::test {

/// `page` with each block from `open` to the first `close` after it replaced by a space.
inline std::string without_blocks(std::string page, const std::string& open,
                                  const std::string& close) {
  for (std::size_t at = page.find(open); at != std::string::npos; at = page.find(open, at)) {
    const std::size_t end = page.find(close, at + open.size());
    if (end == std::string::npos) break;
    page.replace(at, end + close.size() - at, " ");
  }
  return page;
}

/// The text a reader sees: the page without its style sheet and markup, the SVGs' <text>.
/// (Scanned, not std::regex: its matcher recurses once per character, and a plot's <path> of
/// thousands of points overflows the stack.)
inline std::string visible_text(std::string page) {
  page = without_blocks(std::move(page), "<style>", "</style>");
  page = without_blocks(std::move(page), "<desc>", "</desc>");
  page = without_blocks(std::move(page), "<title>", "</title>");
  std::string text;
  text.reserve(page.size());
  std::size_t at = 0;
  while (at < page.size()) {
    const std::size_t open = page.find('<', at);
    const std::size_t close = open == std::string::npos ? open : page.find('>', open);
    if (close == std::string::npos) {  // no more tags
      text.append(page, at, std::string::npos);
      break;
    }
    text.append(page, at, open - at);
    text += ' ';
    at = close + 1;
  }
  return text;
}

/// Each Latin word of three letters or more outside `allowed`, with 60 characters either side.
inline std::vector<std::string> english_left(const std::string& page,
                                             const std::set<std::string>& allowed) {
  std::vector<std::string> left;
  const std::string visible = visible_text(page);
  const std::regex word("[A-Za-z]{3,}");
  for (auto it = std::sregex_iterator(visible.begin(), visible.end(), word);
       it != std::sregex_iterator(); ++it) {
    if (allowed.count(it->str())) continue;
    const auto from = std::max<std::ptrdiff_t>(0, it->position() - 60);
    left.push_back("'" + it->str() + "' in ..." + visible.substr(from, 120));
  }
  return left;
}

}  // namespace foglab::test
