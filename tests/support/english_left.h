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

/// The text a reader sees: the page without its style sheet and markup, the SVGs' <text>.
inline std::string visible_text(std::string page) {
  page = std::regex_replace(page, std::regex("<style>[\\s\\S]*?</style>"), " ");
  page = std::regex_replace(page, std::regex("<desc>[\\s\\S]*?</desc>"), " ");
  page = std::regex_replace(page, std::regex("<title>[\\s\\S]*?</title>"), " ");
  page = std::regex_replace(page, std::regex("<[^>]*>"), " ");
  return page;
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
