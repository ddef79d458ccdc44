#include "tools/cli/tool_modes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace atlas::cli {
namespace {

std::string last_runs;

int RunA(const ToolOptions& o) {
  last_runs = o.values.count("--runs") ? o.values.at("--runs") : "";
  return 7;
}
int RunB(const ToolOptions&) { return 9; }

int Call(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return RunToolMode(static_cast<int>(argv.size()), argv.data(), "tool", "modes\n",
                     {{"a", "runs a", {{"--runs", "N", "how many runs (default 1)"}}, RunA},
                      {"b", "runs b", {}, RunB}});
}

TEST(ToolModes, RunsTheNamedModeWithItsOptions) {
  last_runs.clear();
  EXPECT_EQ(Call({"tool", "a", "--runs", "3"}), 7);
  EXPECT_EQ(last_runs, "3");
  EXPECT_EQ(Call({"tool", "a", "--runs=4"}), 7);
  EXPECT_EQ(last_runs, "4");
  EXPECT_EQ(Call({"tool", "b"}), 9);
}

TEST(ToolModes, AModesHelpDescribesItAndEachOption) {
  testing::internal::CaptureStdout();
  EXPECT_EQ(Call({"tool", "a", "--help"}), 0);
  const std::string help = testing::internal::GetCapturedStdout();
  EXPECT_NE(help.find("runs a"), std::string::npos) << help;
  EXPECT_NE(help.find("--runs N"), std::string::npos) << help;
  EXPECT_NE(help.find("how many runs (default 1)"), std::string::npos) << help;
}

TEST(ToolModes, HelpAndVersionAreZeroAndMistakesAreTwo) {
  testing::internal::CaptureStdout();
  EXPECT_EQ(Call({"tool", "--help"}), 0);
  EXPECT_EQ(Call({"tool", "-h"}), 0);
  EXPECT_EQ(Call({"tool", "a", "--help"}), 0);
  EXPECT_EQ(Call({"tool", "--version"}), 0);
  testing::internal::GetCapturedStdout();
  testing::internal::CaptureStderr();
  EXPECT_EQ(Call({"tool"}), 2);
  EXPECT_EQ(Call({"tool", "c"}), 2);
  EXPECT_EQ(Call({"tool", "b", "--runs", "3"}), 2);  // b takes no --runs
  EXPECT_EQ(Call({"tool", "a", "--runs"}), 2);       // no value
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("tool: no MODE given (a, b)"), std::string::npos) << err;
  EXPECT_NE(err.find("tool: unknown MODE 'c' (a, b)"), std::string::npos) << err;
  EXPECT_NE(err.find("tool: unknown option '--runs'"), std::string::npos) << err;
  EXPECT_NE(err.find("tool: --runs needs a value"), std::string::npos) << err;
}

}  // namespace
}  // namespace atlas::cli
