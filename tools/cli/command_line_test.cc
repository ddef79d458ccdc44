#include "tools/cli/command_line.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace atlas::cli {
namespace {

// A tool with one option of each kind, parsed from `args` (after the tool's name).
struct Tool {
  double range = 8.0;
  int count = 3;
  uint64_t seed = 1;
  std::string out = "out", kind = "a", file;
  bool quiet = false;
  int status = -1;  // Parse's exit status, -1: goes on
  std::string out_text, err_text;

  explicit Tool(std::vector<std::string> args) {
    CommandLine cl("tool", {"tool [options] FILE"}, "Does things.", "Exit status: 0.\n");
    CLI::App& app = cl.app();
    AddPositional(app, "FILE", &file, "the file");
    AddNumber(app, "--range", "M", 0.5, 80, &range, "range (default 8)");
    AddInteger(app, "-n,--count", "N", 1, 10, &count, "how many");
    AddSeed(app, "--seed", &seed, "random seed");
    AddText(app, "-o,--out", "DIR", &out, "output directory");
    AddChoice(app, "--kind", "K", {"a", "b", "c"}, &kind, "the kind");
    AddFlag(app, "--quiet", &quiet, "quiet");
    args.insert(args.begin(), "tool");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    status = cl.Parse(static_cast<int>(argv.size()), argv.data()).value_or(-1);
    out_text = testing::internal::GetCapturedStdout();
    err_text = testing::internal::GetCapturedStderr();
  }
};

TEST(CommandLine, ValuesAfterASpaceOrAnEqualsSign) {
  const Tool t({"--range", "20", "--count=5", "--seed=7", "-o", "d", "--kind=b", "--quiet", "f"});
  EXPECT_EQ(t.status, -1) << t.err_text;
  EXPECT_EQ(t.range, 20.0);
  EXPECT_EQ(t.count, 5);
  EXPECT_EQ(t.seed, 7u);
  EXPECT_EQ(t.out, "d");
  EXPECT_EQ(t.kind, "b");
  EXPECT_TRUE(t.quiet);
  EXPECT_EQ(t.file, "f");
  EXPECT_EQ(Tool({"--out=e", "-n", "2"}).out, "e");
  const Tool dash({"--", "-f"});  // after --, every argument is an argument
  EXPECT_EQ(dash.status, -1) << dash.err_text;
  EXPECT_EQ(dash.file, "-f");
}

TEST(CommandLine, TheLastOfARepeatedOptionCounts) {
  const Tool t({"--range", "10", "--range", "12"});
  EXPECT_EQ(t.status, -1) << t.err_text;
  EXPECT_EQ(t.range, 12.0);
}

TEST(CommandLine, HelpAndVersionExitZeroOnStdout) {
  const Tool help({"--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out_text.rfind("Usage: tool [options] FILE\n", 0), 0u) << help.out_text;
  for (const char* part : {"Does things.", "--range M", "-n,--count N", "Exit status: 0."})
    EXPECT_NE(help.out_text.find(part), std::string::npos) << part << "\n" << help.out_text;
  EXPECT_EQ(Tool({"-h"}).status, 0);
  const Tool version({"--range", "x", "--version"});
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.out_text.rfind("tool ", 0), 0u) << version.out_text;
  EXPECT_TRUE(version.err_text.empty()) << version.err_text;
}

// Every mistake: exit 2, "tool: <what naming the option>" and the pointer to --help.
void ExpectRefused(const std::vector<std::string>& args, const std::string& what) {
  const Tool t(args);
  EXPECT_EQ(t.status, 2) << what;
  EXPECT_EQ(t.err_text, "tool: " + what + "\nTry 'tool --help'.\n");
  EXPECT_TRUE(t.out_text.empty()) << t.out_text;
}

TEST(CommandLine, MistakesNameTheOptionAndExitTwo) {
  ExpectRefused({"--bogus"}, "unknown option '--bogus'");
  ExpectRefused({"--bogus=3", "f"}, "unknown option '--bogus'");
  ExpectRefused({"-x"}, "unknown option '-x'");
  ExpectRefused({"f", "g"}, "unexpected argument 'g'");
  ExpectRefused({"--range"}, "--range needs a value");
  // As getopt does: the word after an option that needs a value is its value.
  ExpectRefused({"--range", "--quiet"}, "--range must be a number in [0.5, 80], got '--quiet'");
  ExpectRefused({"--range", "-1"}, "--range must be a number in [0.5, 80], got '-1'");
  ExpectRefused({"-n"}, "--count needs a value");
  ExpectRefused({"--range", "5x"}, "--range must be a number in [0.5, 80], got '5x'");
  ExpectRefused({"--range="}, "--range needs a value");
  ExpectRefused({"--range", ""}, "--range must be a number in [0.5, 80], got ''");
  ExpectRefused({"--range", "100"}, "--range must be a number in [0.5, 80], got '100'");
  ExpectRefused({"--count", "1.5"}, "--count must be an integer in [1, 10], got '1.5'");
  ExpectRefused({"--seed", "-1"},
                "--seed must be an integer in [0, 18446744073709551615], got '-1'");
  ExpectRefused({"--out", ""}, "--out needs a DIR, got ''");
  ExpectRefused({"--kind", "d"}, "--kind must be one of a, b or c, got 'd'");
}

TEST(CommandLine, HelpNumbersReadBack) {
  EXPECT_EQ(HelpNumber(0.0002), "0.0002");
  EXPECT_EQ(HelpNumber(5e-6), "5e-06");
  EXPECT_EQ(HelpNumber(8.0), "8");
  EXPECT_EQ(HelpNumber(60.0), "60");
  EXPECT_EQ(HelpNumber(1000.0), "1000");
  EXPECT_EQ(HelpNumber(1e6), "1e+06");
  EXPECT_EQ(HelpNumber(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(LongName("-o,--out"), "--out");
}

}  // namespace
}  // namespace atlas::cli
