// The library speaks the library's language: no string literal in src/ or
// include/ names a command-line flag (a program calling the library has no
// flags). Its messages name the API field instead (ReadOptions::
// sample_rate_hz, TauGrid::min_clusters, parse_tau_grid("...")), and the CLI
// translates them in one place (apps/foglab/cli_common.h, in_cli_terms();
// tests/cli/cli_bad_input_test.cc checks the flags reach the user).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace foglab {
namespace {

namespace fs = std::filesystem;

// The string literals of a C++ source with their line numbers: comments and
// character literals skipped, escapes kept as written, raw strings read to
// their delimiter.
std::vector<std::pair<int, std::string>> string_literals(const std::string& code) {
  std::vector<std::pair<int, std::string>> out;
  int line = 1;
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    if (c == '\n') {
      ++line;
    } else if (code.compare(i, 2, "//") == 0) {
      while (i < code.size() && code[i] != '\n') ++i;
      --i;
    } else if (code.compare(i, 2, "/*") == 0) {
      const std::size_t end = code.find("*/", i + 2);
      for (std::size_t k = i; k < end; ++k) line += code[k] == '\n';
      i = end + 1;
    } else if (c == '\'') {
      for (++i; i < code.size() && code[i] != '\''; ++i) {
        if (code[i] == '\\') ++i;
      }
    } else if (code.compare(i, 2, "R\"") == 0) {
      const std::size_t open = code.find('(', i);
      const std::string close = ")" + code.substr(i + 2, open - i - 2) + "\"";
      const std::size_t end = code.find(close, open);
      out.emplace_back(line, code.substr(open + 1, end - open - 1));
      for (std::size_t k = i; k < end; ++k) line += code[k] == '\n';
      i = end + close.size() - 1;
    } else if (c == '"') {
      std::string text;
      for (++i; i < code.size() && code[i] != '"'; ++i) {
        if (code[i] == '\\') text += code[i++];
        text += code[i];
      }
      out.emplace_back(line, text);
    }
  }
  return out;
}

TEST(LibraryMessages, LiteralsAreFoundWhereTheyAre) {
  const std::string code =
      "// \"--fs\" in a comment\nthrow E(\"give --fs\"); /* \"--x\"\n */ char q = '\"';\n"
      "auto r = R\"(--raw)\"; auto s = \"a \\\"--quoted\\\" b\";";
  const auto found = string_literals(code);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0], std::make_pair(2, std::string("give --fs")));
  EXPECT_EQ(found[1], std::make_pair(4, std::string("--raw")));
  EXPECT_EQ(found[2], std::make_pair(4, std::string("a \\\"--quoted\\\" b")));
}

TEST(LibraryMessages, NoLibrarySourceNamesACommandLineFlag) {
  const std::regex flag("(^|[^-A-Za-z0-9])--[a-z]");
  // Arguments the library passes to other programs, not words for a user.
  const std::vector<std::string> allowed = {"src/report/plot.cc: --version"};
  std::vector<std::string> offenders;
  std::size_t files = 0;
  for (const char* top : {"src", "include"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(FOGLAB_SOURCE_DIR) / top)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cc" && ext != ".h" && ext != ".in") continue;
      ++files;
      std::ifstream in(entry.path());
      std::stringstream code;
      code << in.rdbuf();
      const std::string name = fs::relative(entry.path(), FOGLAB_SOURCE_DIR).generic_string();
      for (const auto& [line, text] : string_literals(code.str())) {
        if (!std::regex_search(text, flag)) continue;
        const std::string where = name + ": " + text;
        if (std::find(allowed.begin(), allowed.end(), where) != allowed.end()) continue;
        offenders.push_back(name + ":" + std::to_string(line) + ": \"" + text + "\"");
      }
    }
  }
  EXPECT_GT(files, 50u) << "the sources were not found under " << FOGLAB_SOURCE_DIR;
  std::string list;
  for (const std::string& o : offenders) list += "\n  " + o;
  EXPECT_TRUE(offenders.empty()) << "library messages that name command-line flags:" << list;
}

}  // namespace
}  // namespace foglab
