// Issue 22, part 1: what an output path leads to is never destroyed and an
// output is never lost silently (core/output.h). An output that is an input
// of the run or another output of it is refused before anything is written;
// a symbolic link keeps pointing at the new content; a FIFO (like a device
// such as /dev/null) is written in place, not replaced by a regular file;
// standard output takes one output at most, and a lost standard output
// (a full disk, a closed stream) fails the run with exit 3.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using test::quote;
using ::testing::HasSubstr;

// A short record to analyse, made by foglab itself.
std::string make_record(const test::TempDir& dir) {
  const std::string record = dir.file("run.csv");
  const test::CliRun g =
      test::run_foglab("generate --N 0.3 --fs 10 --hours 0.2 --seed 3 --out " + quote(record));
  EXPECT_EQ(g.exit_code, 0) << g.err;
  return record;
}

// Every file in the directory (temporaries included, they start with '.').
std::vector<std::string> listing(const test::TempDir& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path())) names.push_back(e.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(CliOutputs, AnOutputThatIsAnInputOrAnotherOutputIsRefused) {
  const test::TempDir dir;
  const std::string record = make_record(dir);
  const std::string before = test::read_file(record);
  const std::vector<std::string> files = listing(dir);
  struct Case {
    std::string args, words;
  };
  fs::create_symlink("run.csv", dir / "alias.csv");
  const Case cases[] = {
      {"allan " + quote(record) + " --json " + quote(record), "is the input FILE"},
      {"psd " + quote(record) + " --csv " + quote(dir / "alias.csv"), "is the input FILE"},
      {"analyze " + quote(record) + " --report " + quote(dir / "." / "run.csv"),
       "is the input FILE"},
      {"analyze " + quote(record) + " --json " + quote(dir / "a.out") + " --csv " +
           quote(dir / "sub" / ".." / "a.out"),
       "are the same file"},
      {"analyze " + quote(record) + " --json - --csv -", "only one output can go to standard"},
      {"generate --N 0.3 --fs 10 --hours 0.01 --out " + quote(dir / "x.mat") + " --truth " +
           quote(dir / "x.mat"),
       "are the same file"},
  };
  fs::create_directory(dir / "sub");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const test::CliRun r = test::run_foglab(c.args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_THAT(r.err, HasSubstr(c.words));
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(test::read_file(record), before);  // the recording is intact
  }
  fs::remove(dir / "sub");
  fs::remove(dir / "alias.csv");
  EXPECT_EQ(listing(dir), files);  // nothing written, no temporary left
}

TEST(CliOutputs, ALinkKeepsPointingAtTheNewContent) {
  const test::TempDir dir;
  const std::string record = make_record(dir);
  std::ofstream(dir / "target.json") << "old\n";
  fs::create_symlink("target.json", dir / "link.json");
  const test::CliRun r =
      test::run_foglab("allan " + quote(record) + " --json " + quote(dir / "link.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link.json")));
  EXPECT_EQ(fs::read_symlink(dir / "link.json"), "target.json");
  EXPECT_THAT(test::read_file(dir / "target.json"), HasSubstr("\"tau_s\""));
}

TEST(CliOutputs, AFifoIsWrittenInPlaceNotReplaced) {
  // What a device such as /dev/null gets too: the suite runs as root on CI,
  // where replacing /dev/null would break the machine, so a FIFO stands in.
  const test::TempDir dir;
  const std::string record = make_record(dir);
  for (const std::string& target : {std::string("out.json"), std::string("out.f64")}) {
    SCOPED_TRACE(target);
    const fs::path fifo = dir / target;
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::string received;
    std::thread reader([&] { received = test::read_file(fifo); });
    const test::CliRun r =
        target == "out.json"
            ? test::run_foglab("allan " + quote(record) + " --json " + quote(fifo))
            : test::run_foglab("generate --N 0.3 --fs 10 --hours 0.01 --out " + quote(fifo));
    reader.join();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::is_fifo(fs::status(fifo)));
    if (target == "out.json") {
      EXPECT_THAT(received, HasSubstr("\"tau_s\""));
    } else {
      EXPECT_EQ(received.size(), 360u * 8u);  // 36 s at 10 Hz as float64
    }
  }
}

TEST(CliOutputs, ALostStandardOutputFailsTheRun) {
  const test::TempDir dir;
  const std::string record = make_record(dir);
  auto status_of = [&](const std::string& args, const std::string& redirect) {
    const std::string command = std::string("'") + FOGLAB_CLI_PATH + "' " + args + " " + redirect +
                                " 2> " + quote(dir / "err");
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  for (const std::string& args :
       {"allan " + quote(record) + " --json -", "analyze " + quote(record)}) {
    SCOPED_TRACE(args);
    EXPECT_EQ(status_of(args, "> /dev/full"), 3);
    EXPECT_THAT(test::read_file(dir / "err"), HasSubstr("cannot write to standard output"));
    EXPECT_EQ(status_of(args, ">&-"), 3);
    EXPECT_EQ(status_of(args, "> /dev/null"), 0);
  }
}

TEST(CliOutputs, DevStdoutIsStandardOutputUnderAnotherName) {
  // --json /dev/stdout with the shell's redirection to a file: written
  // through standard output, in order with the table (a second descriptor
  // to the same file had written over the JSON's start); and it counts as
  // standard output when another output is "-".
  const test::TempDir dir;
  const std::string record = make_record(dir);
  const fs::path captured = dir / "captured.txt";
  const std::string command = std::string("'") + FOGLAB_CLI_PATH + "' allan " + quote(record) +
                              " --json /dev/stdout > " + quote(captured) + " 2> /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string text = test::read_file(captured);
  const std::size_t json_end = text.find("\n}\n");
  ASSERT_NE(json_end, std::string::npos) << text;
  EXPECT_TRUE(nlohmann::json::accept(text.substr(0, json_end + 3)));
  EXPECT_THAT(text.substr(json_end + 3), HasSubstr("oadev of"));  // the table after it

  const test::CliRun r = test::run_foglab("allan " + quote(record) + " --json - --csv /dev/stdout");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("only one output can go to standard output"));
}

}  // namespace
}  // namespace foglab
