#include "tools/cli/command_line.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "core/common/version.h"

namespace atlas::cli {
namespace {

// Usage first, then the description, the options and the footer: the layout help2man reads.
class Formatter : public CLI::Formatter {
 public:
  explicit Formatter(std::string usage) : usage_(std::move(usage)) {}
  std::string make_help(const CLI::App* app, std::string name,
                        CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    std::ostringstream out;
    out << (app->get_parent() == nullptr ? usage_ : make_usage(app, name)) << "\n";
    std::string description = app->get_description();
    while (!description.empty() && description.back() == '\n') description.pop_back();
    if (!description.empty()) out << description << "\n";
    out << make_positionals(app) << make_groups(app, mode) << make_subcommands(app, mode);
    const std::string footer = make_footer(app);
    if (!footer.empty()) out << "\n" << footer;
    return out.str();
  }

 private:
  std::string usage_;
};

// The option a CLI11 message starts with ("--x: 1 required M missing"), or "".
std::string OptionOf(const std::string& message) {
  const size_t colon = message.find(':');
  if (colon == std::string::npos || message.empty() || message[0] != '-') return "";
  return message.substr(0, colon);
}

}  // namespace

std::string LongName(const std::string& names) {
  std::string best;
  std::stringstream in(names);
  for (std::string name; std::getline(in, name, ',');) {
    if (name.size() > best.size()) best = name;
  }
  return best;
}

std::string HelpNumber(double value) {
  // The fewest digits may not be the shortest text: 60 is "6e+01" with one digit, "60" with two.
  std::string best;
  for (int digits = 1; digits <= 17; ++digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    double back = 0.0;
    if (ParseNumber(text, &back) && back == value && (best.empty() || strlen(text) < best.size()))
      best = text;
  }
  return best;
}

CommandLine::CommandLine(std::string tool, std::vector<std::string> usage, std::string description,
                         std::string footer)
    : tool_(std::move(tool)), app_(std::make_unique<CLI::App>(std::move(description), tool_)) {
  std::string lines;
  for (size_t i = 0; i < usage.size(); ++i)
    lines += (i == 0 ? "Usage: " : "       ") + usage[i] + "\n";
  auto formatter = std::make_shared<Formatter>(lines);
  formatter->column_width(27);
  formatter->label("Positionals", "Arguments");
  app_->formatter(formatter);
  app_->footer(std::move(footer));
  app_->set_help_flag("-h,--help", "this text");
  // Listed for the help; Parse answers it before CLI11 reads the line.
  app_->add_flag_callback(
      "--version", [] {}, "the version");
  app_->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  // Unknown options are left over and named by Parse, one message for every tool.
  app_->allow_extras();
}

CommandLine::~CommandLine() = default;

std::string CommandLine::Help() const { return app_->help(); }

std::optional<int> CommandLine::Parse(int argc, char** argv) {
  // --version before anything else, as --help: a tool's version is printed whatever else the
  // command line says.
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--version") {
      std::fputs(VersionLine(tool_.c_str()).c_str(), stdout);
      return 0;
    }
    if (std::string(argv[i]) == "--") break;
  }
  try {
    app_->parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app_->help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app_->help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::ArgumentMismatch& e) {
    const std::string option = OptionOf(e.what());
    return Usage(option.empty() ? e.what() : option + " needs a value");
  } catch (const CLI::ParseError& e) {
    return Usage(e.what());
  }
  for (const std::string& extra : app_->remaining(true)) {
    if (extra == "--") continue;  // the end of the options, kept by allow_extras
    if (extra.size() > 1 && extra[0] == '-') {
      return Usage("unknown option '" + extra.substr(0, extra.find('=')) + "'");
    }
    return Usage("unexpected argument '" + extra + "'");
  }
  return std::nullopt;
}

int CommandLine::Usage(const std::string& what) const {
  std::fprintf(stderr, "%s: %s\nTry '%s --help'.\n", tool_.c_str(), what.c_str(), tool_.c_str());
  return kExitUsage;
}

Option AddValue(CLI::App& app, const std::string& names, const std::string& value_name,
                std::function<std::string(const std::string&)> take, const std::string& help) {
  CLI::Option* option = app.add_option_function<std::string>(
      names,
      [take = std::move(take)](const std::string& value) {
        if (std::string error = take(value); !error.empty())
          throw CLI::ValidationError(error, CLI::ExitCodes::ValidationError);
      },
      help);
  option->type_name(value_name);
  return Option(option);
}

Option AddNumber(CLI::App& app, const std::string& names, const std::string& value_name, double lo,
                 double hi, std::function<void(double)> set, const std::string& help) {
  return AddValue(
      app, names, value_name,
      [option = LongName(names), lo, hi, set = std::move(set)](const std::string& v) {
        std::string error;
        double x = 0.0;
        if (NumberArgument(option, v.c_str(), lo, hi, x, error)) set(x);
        return error;
      },
      help);
}

Option AddNumber(CLI::App& app, const std::string& names, const std::string& value_name, double lo,
                 double hi, double* out, const std::string& help) {
  return AddNumber(
      app, names, value_name, lo, hi, [out](double x) { *out = x; }, help);
}

Option AddSeed(CLI::App& app, const std::string& names, uint64_t* out, const std::string& help) {
  return AddValue(
      app, names, "N",
      [option = LongName(names), out](const std::string& v) {
        std::string error;
        SeedArgument(option, v.c_str(), *out, error);
        return error;
      },
      help);
}

Option AddText(CLI::App& app, const std::string& names, const std::string& value_name,
               std::string* out, const std::string& help) {
  return AddValue(
      app, names, value_name,
      [option = LongName(names), value_name, out](const std::string& v) {
        if (v.empty()) return option + " needs a " + value_name + ", got ''";
        *out = v;
        return std::string();
      },
      help);
}

Option AddChoice(CLI::App& app, const std::string& names, const std::string& value_name,
                 std::vector<std::string> choices, std::string* out, const std::string& help) {
  return AddValue(
      app, names, value_name,
      [option = LongName(names), choices = std::move(choices), out](const std::string& v) {
        std::string list;
        for (size_t i = 0; i < choices.size(); ++i) {
          if (choices[i] == v) {
            *out = v;
            return std::string();
          }
          list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
        }
        return option + " must be one of " + list + ", got '" + v + "'";
      },
      help);
}

Option AddFlag(CLI::App& app, const std::string& names, bool* out, const std::string& help) {
  return Option(app.add_flag_callback(
      names, [out] { *out = true; }, help));
}

Option AddPositional(CLI::App& app, const std::string& name, std::string* out,
                     const std::string& help) {
  return Option(app.add_option(name, *out, help)->type_name(""));
}

Option AddPositional(CLI::App& app, const std::string& name, std::vector<std::string>* out,
                     const std::string& help) {
  return Option(app.add_option(name, *out, help)->type_name(""));
}

Option& Option::Group(const std::string& group) {
  option_->group(group);
  return *this;
}

Option& Option::Each(std::function<void(const std::string&)> given) {
  option_->each(std::move(given));
  return *this;
}

Option& Option::Repeatable() {
  option_->trigger_on_parse();
  return *this;
}

bool Given(const CLI::App& app, const std::string& name) { return app.count(name) > 0; }

}  // namespace atlas::cli
