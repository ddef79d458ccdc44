#pragma once
// The command line of every atlasd tool (CLI11), with one convention for all of them:
//   --opt value and --opt=value; an option given twice: the last one counts;
//   -h, --help: the help on stdout, exit 0; --version: VersionLine (core/common/version.h) on
//   stdout, exit 0;
//   a bad command line: "<tool>: <what>" and "Try '<tool> --help'." on stderr, exit 2, <what>
//   naming the option: "unknown option '--x'", "--x needs a value", "unexpected argument 'y'",
//   or the value's fault ("--x must be a number in [0, 1], got '5x'": the checks and messages
//   of core/common/parse_number.h, made while the command line is read).

#include <concepts>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/common/parse_number.h"

// CLI11 is included by tools/cli/*.cc only: its headers cost a translation unit about ten
// seconds of compile time, so the tools see it through the declarations below.
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace atlas::cli {

inline constexpr int kExitUsage = 2;

class CommandLine {
 public:
  // `usage`: the forms of the command, each without the word "Usage" ("atlas-refine [options]
  // DIR"); `description`: what the tool does, printed after them; `footer`: printed after the
  // options (exit status, examples). Adds -h/--help and --version.
  CommandLine(std::string tool, std::vector<std::string> usage, std::string description,
              std::string footer = "");
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  CLI::App& app() { return *app_; }
  const std::string& tool() const { return tool_; }

  // Reads argv. nullopt: the tool goes on; otherwise its exit status: 0 after --help or
  // --version (printed), 2 after a bad command line (message printed).
  std::optional<int> Parse(int argc, char** argv);
  // What the tool finds wrong with the command line after Parse (two options that exclude each
  // other, a missing argument): the message as above; returns 2.
  int Usage(const std::string& what) const;
  // The text --help prints.
  std::string Help() const;

 private:
  std::string tool_;
  std::unique_ptr<CLI::App> app_;
};

// One option of a command line, as the Add* functions below return it.
class Option {
 public:
  explicit Option(CLI::Option* option) : option_(option) {}
  // Lists the option under the heading `group` in the help.
  Option& Group(const std::string& group);
  // Calls `given` with the option's value each time the option is given, after the value's check.
  Option& Each(std::function<void(const std::string&)> given);
  // Hands every value given to the option's check, not only the last one (a repeatable option).
  Option& Repeatable();

 private:
  CLI::Option* option_;
};

// The option's long name in `names` ("-o,--out" -> "--out"), as messages name it.
std::string LongName(const std::string& names);

// An option whose one value `take` accepts (an empty return) or refuses (the message naming the
// option, printed as a bad command line). `value_name` is the value's name in the help ("M").
Option AddValue(CLI::App& app, const std::string& names, const std::string& value_name,
                std::function<std::string(const std::string&)> take, const std::string& help);

// A number in [lo, hi] (NumberArgument) handed to `set`, or stored in `out`.
Option AddNumber(CLI::App& app, const std::string& names, const std::string& value_name, double lo,
                 double hi, std::function<void(double)> set, const std::string& help);
Option AddNumber(CLI::App& app, const std::string& names, const std::string& value_name, double lo,
                 double hi, double* out, const std::string& help);
// An integer in [lo, hi] (IntegerArgument); [lo, hi] must lie within Int.
template <std::integral Int>
Option AddInteger(CLI::App& app, const std::string& names, const std::string& value_name,
                  int64_t lo, int64_t hi, Int* out, const std::string& help) {
  return AddValue(
      app, names, value_name,
      [names, lo, hi, out](const std::string& v) {
        std::string error;
        IntegerArgument(LongName(names), v.c_str(), lo, hi, *out, error);
        return error;
      },
      help);
}
// A random seed: any integer in [0, 2^64 - 1] (SeedArgument).
Option AddSeed(CLI::App& app, const std::string& names, uint64_t* out, const std::string& help);
// A text that must not be empty (a file, a directory, a name).
Option AddText(CLI::App& app, const std::string& names, const std::string& value_name,
               std::string* out, const std::string& help);
// One of `choices` ("--x must be one of a, b or c, got 'd'").
Option AddChoice(CLI::App& app, const std::string& names, const std::string& value_name,
                 std::vector<std::string> choices, std::string* out, const std::string& help);
// A positional argument (one, or all of them) named `name` in the help.
Option AddPositional(CLI::App& app, const std::string& name, std::string* out,
                     const std::string& help);
Option AddPositional(CLI::App& app, const std::string& name, std::vector<std::string>* out,
                     const std::string& help);
// A flag without a value: sets `*out` to true.
Option AddFlag(CLI::App& app, const std::string& names, bool* out, const std::string& help);

// Whether the option named `name` ("--x") was given on the command line read by Parse.
bool Given(const CLI::App& app, const std::string& name);

// A number for a help text: the shortest form that reads back as `value` ("0.0002", "5e-06").
std::string HelpNumber(double value);

}  // namespace atlas::cli
