#include "tools/eval/tool_modes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace atlas::eval {
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
  return RunToolMode(static_cast<int>(argv.size()), argv.data(), "tool", "usage\n",
                     {{"a", {"--runs"}, RunA}, {"b", {}, RunB}});
}

TEST(ToolModes, RunsTheNamedModeWithItsOptions) {
  last_runs.clear();
  EXPECT_EQ(Call({"tool", "a", "--runs", "3"}), 7);
  EXPECT_EQ(last_runs, "3");
  EXPECT_EQ(Call({"tool", "b"}), 9);
}

TEST(ToolModes, HelpIsZeroAndMistakesAreTwo) {
  EXPECT_EQ(Call({"tool", "--help"}), 0);
  EXPECT_EQ(Call({"tool", "-h"}), 0);
  EXPECT_EQ(Call({"tool"}), 2);
  EXPECT_EQ(Call({"tool", "c"}), 2);
  EXPECT_EQ(Call({"tool", "b", "--runs", "3"}), 2);  // b takes no --runs
  EXPECT_EQ(Call({"tool", "a", "--runs"}), 2);       // no value
}

}  // namespace
}  // namespace atlas::eval
