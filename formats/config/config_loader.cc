#include "formats/config/config_loader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <any>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ostream>
#include <set>
#include <sstream>

#include "formats/config/config_schema.h"

namespace atlas {
namespace {

std::string Join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

template <typename T>
std::string FormatNumber(T v) {
  if constexpr (std::is_integral_v<T>) {
    return std::to_string(v);
  } else {
    std::ostringstream s;
    s << v;
    return s.str();
  }
}

std::string TypeName(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

// The value checks shared by the file reader and Validate(); empty string = acceptable.
template <typename T>
std::string RangeProblem(T v, T lo, T hi) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return "must be a finite number, got " + FormatNumber(v);
  }
  if (v < lo || v > hi) {
    return "must be between " + FormatNumber(lo) + " and " + FormatNumber(hi) + ", got " +
           FormatNumber(v);
  }
  return "";
}

template <typename T, typename List>
std::string OneOfProblem(T v, const List& allowed) {
  std::string list;
  for (T a : allowed) {
    if (std::fabs(static_cast<double>(v) - static_cast<double>(a)) < 1e-9) return "";
    list += (list.empty() ? "" : ", ") + FormatNumber(a);
  }
  return "must be one of " + list + ", got " + FormatNumber(v);
}

template <typename E, size_t N>
std::string EnumNameList(const config::EnumNames<E, N>& names) {
  std::string list;
  for (const auto& [name, value] : names) {
    list += (list.empty() ? "\"" : ", \"") + std::string(name) + "\"";
  }
  return list;
}

// Visits the schema against a parsed TOML document, filling DaemonOptions and errors.
class TomlReader {
 public:
  TomlReader(const toml::table& root, std::string file, std::vector<ConfigError>* errors)
      : file_(std::move(file)), errors_(errors) {
    frames_.push_back(Frame{&root, "", {}});
  }

  // Reports the unknown keys of the top level; call after VisitOptions().
  void Finish() { ReportUnknown(frames_.front()); }

  template <typename F>
  void Section(const char* name, F body) {
    const toml::node* n = Take(name);
    if (n == nullptr) return;
    if (!n->is_table()) {
      Error(name, n->source(), "expected a table of keys, got " + TypeName(*n));
      return;
    }
    frames_.push_back(Frame{n->as_table(), Join(frames_.back().prefix, name), {}});
    body();
    ReportUnknown(frames_.back());
    frames_.pop_back();
  }

  void Bool(const char* key, bool& v) {
    if (const toml::node* n = TakeOfType(key, toml::node_type::boolean, "a boolean")) {
      v = n->as_boolean()->get();
    }
  }

  void Int(const char* key, int& v, int lo, int hi) {
    int64_t x;
    if (const toml::node* n = TakeInt(key, &x)) {
      if (Check(key, *n, RangeProblem<int64_t>(x, lo, hi))) v = static_cast<int>(x);
    }
  }

  void IntOneOf(const char* key, int& v, std::initializer_list<int> allowed) {
    int64_t x;
    if (const toml::node* n = TakeInt(key, &x)) {
      if (Check(key, *n, OneOfProblem<int64_t>(x, allowed))) {
        v = static_cast<int>(x);
      }
    }
  }

  void Double(const char* key, double& v, double lo, double hi) {
    double x;
    if (const toml::node* n = TakeDouble(key, &x)) {
      if (Check(key, *n, RangeProblem(x, lo, hi))) v = x;
    }
  }

  void DoubleOneOf(const char* key, double& v, std::initializer_list<double> allowed) {
    double x;
    if (const toml::node* n = TakeDouble(key, &x)) {
      if (Check(key, *n, OneOfProblem(x, allowed))) v = x;
    }
  }

  void String(const char* key, std::string& v, config::StringCheck check) {
    if (const toml::node* n = TakeOfType(key, toml::node_type::string, "a string")) {
      const std::string& s = n->as_string()->get();
      if (Check(key, *n, check(s))) v = s;
    }
  }

  template <typename E, size_t N>
  void Enum(const char* key, E& v, const config::EnumNames<E, N>& names) {
    const toml::node* n = TakeOfType(key, toml::node_type::string, "a string");
    if (n == nullptr) return;
    const std::string& s = n->as_string()->get();
    for (const auto& [name, value] : names) {
      if (s == name) {
        v = value;
        return;
      }
    }
    Error(key, n->source(), "must be one of " + EnumNameList(names) + ", got \"" + s + "\"");
  }

  void IntList(const char* key, std::vector<int>& v, int lo, int hi, size_t max_size) {
    const toml::node* n = TakeOfType(key, toml::node_type::array, "an array of integers");
    if (n == nullptr) return;
    const toml::array& a = *n->as_array();
    if (a.size() > max_size) {
      Error(key, n->source(), "must have at most " + std::to_string(max_size) + " elements");
      return;
    }
    std::vector<int> out;
    bool good = true;
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string element = std::string(key) + "[" + std::to_string(i) + "]";
      if (!a[i].is_integer()) {
        Error(element, a[i].source(), "expected an integer, got " + TypeName(a[i]));
        good = false;
        continue;
      }
      const int64_t x = a[i].as_integer()->get();
      const std::string problem = RangeProblem<int64_t>(x, lo, hi);
      if (!problem.empty()) {
        Error(element, a[i].source(), problem);
        good = false;
        continue;
      }
      out.push_back(static_cast<int>(x));
    }
    if (good) v = std::move(out);
  }

  void Error(const std::string& key, const toml::source_region& where, const std::string& message) {
    errors_->push_back(ConfigError{file_, static_cast<int>(where.begin.line),
                                   static_cast<int>(where.begin.column),
                                   Join(frames_.back().prefix, key), message});
  }

 private:
  struct Frame {
    const toml::table* table;
    std::string prefix;
    std::set<std::string> taken;
  };

  const toml::node* Take(const char* key) {
    Frame& f = frames_.back();
    f.taken.insert(key);
    return f.table->get(key);
  }

  const toml::node* TakeOfType(const char* key, toml::node_type type, const char* expected) {
    const toml::node* n = Take(key);
    if (n == nullptr) return nullptr;
    if (n->type() != type) {
      Error(key, n->source(), std::string("expected ") + expected + ", got " + TypeName(*n));
      return nullptr;
    }
    return n;
  }

  const toml::node* TakeInt(const char* key, int64_t* x) {
    const toml::node* n = TakeOfType(key, toml::node_type::integer, "an integer");
    if (n != nullptr) *x = n->as_integer()->get();
    return n;
  }

  // Integers are accepted where a floating-point number is expected (track_width_m = 1).
  const toml::node* TakeDouble(const char* key, double* x) {
    const toml::node* n = Take(key);
    if (n == nullptr) return nullptr;
    if (n->is_floating_point()) {
      *x = n->as_floating_point()->get();
    } else if (n->is_integer()) {
      *x = static_cast<double>(n->as_integer()->get());
    } else {
      Error(key, n->source(), "expected a number, got " + TypeName(*n));
      return nullptr;
    }
    return n;
  }

  bool Check(const char* key, const toml::node& n, const std::string& problem) {
    if (problem.empty()) return true;
    Error(key, n.source(), problem);
    return false;
  }

  void ReportUnknown(const Frame& f) {
    for (const auto& [k, node] : *f.table) {
      const std::string name(k.str());
      if (f.taken.count(name) != 0) continue;
      errors_->push_back(ConfigError{
          file_, static_cast<int>(k.source().begin.line), static_cast<int>(k.source().begin.column),
          Join(f.prefix, name), node.is_table() ? "unknown section" : "unknown key"});
    }
  }

  std::string file_;
  std::vector<ConfigError>* errors_;
  std::vector<Frame> frames_;
};

// The dotted key a schema visitor (config_schema.h) is at: its sections, joined.
class KeyPath {
 public:
  template <typename F>
  void Section(const char* name, F body) {
    const std::string saved = prefix_;
    prefix_ = Join(prefix_, name);
    body();
    prefix_ = saved;
  }

 protected:
  std::string prefix_;
};

// Visits the schema against values already in DaemonOptions (for Validate()).
class ValueChecker : public KeyPath {
 public:
  explicit ValueChecker(std::vector<std::string>* problems) : problems_(problems) {}

  void Bool(const char*, bool&) {}
  void Int(const char* key, int& v, int lo, int hi) { Note(key, RangeProblem(v, lo, hi)); }
  void IntOneOf(const char* key, int& v, std::initializer_list<int> allowed) {
    Note(key, OneOfProblem(v, allowed));
  }
  void Double(const char* key, double& v, double lo, double hi) {
    Note(key, RangeProblem(v, lo, hi));
  }
  void DoubleOneOf(const char* key, double& v, std::initializer_list<double> allowed) {
    Note(key, OneOfProblem(v, allowed));
  }
  void String(const char* key, std::string& v, config::StringCheck check) { Note(key, check(v)); }
  template <typename E, size_t N>
  void Enum(const char* key, E& v, const config::EnumNames<E, N>& names) {
    for (const auto& entry : names) {
      if (entry.second == v) return;
    }
    Note(key, "must be one of " + EnumNameList(names));
  }
  void IntList(const char* key, std::vector<int>& v, int lo, int hi, size_t max_size) {
    if (v.size() > max_size)
      Note(key, "must have at most " + std::to_string(max_size) + " elements");
    for (int x : v) Note(key, RangeProblem(x, lo, hi));
  }

 private:
  void Note(const char* key, const std::string& problem) {
    if (!problem.empty()) problems_->push_back(Join(prefix_, key) + ": " + problem);
  }

  std::vector<std::string>* problems_;
};

// Visits the schema writing every value as text (FlattenOptions()).
class Flattener : public KeyPath {
 public:
  std::map<std::string, std::string> values;

  void Bool(const char* k, bool& v) { values[Join(prefix_, k)] = v ? "true" : "false"; }
  void Int(const char* k, int& v, int, int) { values[Join(prefix_, k)] = FormatNumber(v); }
  void IntOneOf(const char* k, int& v, std::initializer_list<int>) {
    values[Join(prefix_, k)] = FormatNumber(v);
  }
  void Double(const char* k, double& v, double, double) {
    values[Join(prefix_, k)] = FormatNumber(v);
  }
  void DoubleOneOf(const char* k, double& v, std::initializer_list<double>) {
    values[Join(prefix_, k)] = FormatNumber(v);
  }
  void String(const char* k, std::string& v, config::StringCheck) {
    values[Join(prefix_, k)] = "\"" + v + "\"";
  }
  template <typename E, size_t N>
  void Enum(const char* k, E& v, const config::EnumNames<E, N>& names) {
    std::string& out = values[Join(prefix_, k)];
    for (const auto& [name, value] : names) {
      if (value == v) out = "\"" + std::string(name) + "\"";
    }
  }
  void IntList(const char* k, std::vector<int>& v, int, int, size_t) {
    std::string s = "[";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + FormatNumber(v[i]);
    values[Join(prefix_, k)] = s + "]";
  }
};

// Visits the schema to copy one key's value from one DaemonOptions into another.
class KeyCopier : public KeyPath {
 public:
  explicit KeyCopier(std::string key) : key_(std::move(key)) {}

  void Copy(const DaemonOptions& from, DaemonOptions* to) {
    DaemonOptions source = from;  // the visitor takes mutable references; nothing is changed
    taking_ = true;
    config::VisitOptions(*this, source);
    taking_ = false;
    config::VisitOptions(*this, *to);
  }

  void Bool(const char* k, bool& v) { At(k, v); }
  void Int(const char* k, int& v, int, int) { At(k, v); }
  void IntOneOf(const char* k, int& v, std::initializer_list<int>) { At(k, v); }
  void Double(const char* k, double& v, double, double) { At(k, v); }
  void DoubleOneOf(const char* k, double& v, std::initializer_list<double>) { At(k, v); }
  void String(const char* k, std::string& v, config::StringCheck) { At(k, v); }
  template <typename E, size_t N>
  void Enum(const char* k, E& v, const config::EnumNames<E, N>&) {
    At(k, v);
  }
  void IntList(const char* k, std::vector<int>& v, int, int, size_t) { At(k, v); }

 private:
  template <typename T>
  void At(const char* k, T& v) {
    if (Join(prefix_, k) != key_) return;
    if (taking_) {
      value_ = v;
    } else {
      v = std::any_cast<T>(value_);
    }
  }

  std::string key_;
  bool taking_ = true;
  std::any value_;
};

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

// The keys of the file that cause problem (a line of derived(options)): those set to something
// other than their default without which the problem goes away.
std::vector<std::string> KeysCausing(const std::string& problem, const DaemonOptions& options,
                                     const DerivedCheck& derived) {
  const DaemonOptions defaults;
  const std::map<std::string, std::string> given = FlattenOptions(options);
  const std::map<std::string, std::string> plain = FlattenOptions(defaults);
  std::vector<std::string> keys;
  for (const auto& [key, value] : given) {
    if (plain.at(key) == value) continue;
    DaemonOptions without = options;
    KeyCopier(key).Copy(defaults, &without);
    const std::vector<std::string> left = Lines(derived(without));
    if (std::find(left.begin(), left.end(), problem) == left.end()) keys.push_back(key);
  }
  return keys;
}

ConfigResult LoadFromTable(const toml::table& root, const std::string& file,
                           const DerivedCheck& derived) {
  ConfigResult result;
  TomlReader reader(root, file, &result.errors);
  config::VisitOptions(reader, result.options);
  reader.Finish();
  // Every rule between keys whose values were read without error is checked in the same run,
  // so that one --check-config lists every problem.
  std::vector<std::string> bad_keys;
  for (const ConfigError& e : result.errors) bad_keys.push_back(e.key);
  const auto usable = [&](const std::string& key) {
    for (const std::string& b : bad_keys)
      if (b.empty() || key == b || key.rfind(b + ".", 0) == 0) return false;
    return true;
  };
  const size_t read_errors = result.errors.size();
  const auto report = [&](const std::string& key, const std::string& message) {
    const toml::node_view<const toml::node> n = root.at_path(key);
    const toml::source_region where = n ? n.node()->source() : toml::source_region{};
    result.errors.push_back(ConfigError{file, static_cast<int>(where.begin.line),
                                        static_cast<int>(where.begin.column), key, message});
  };
  config::CrossCheck(result.options, report, usable);
  // The modules' own checks, unless a rule between keys is broken (they would say it again).
  // A key with an error keeps its default, which no derived problem is blamed on.
  if (result.errors.size() > read_errors || !derived) return result;
  // What the modules (atlas, local maps, loop, device readers) refuse although the file's own
  // ranges allow it: named at the keys that cause it, else at the file.
  for (const std::string& problem : Lines(derived(result.options))) {
    const std::vector<std::string> keys = KeysCausing(problem, result.options, derived);
    for (const std::string& key : keys) {
      report(key, "refused by the module it configures (" + problem +
                      "); choose another value (config/atlasd.toml gives each key's range)");
    }
    if (keys.empty()) {
      result.errors.push_back(ConfigError{
          file, 0, 0, "",
          "refused by the modules it configures (" + problem +
              "); no single key of the file causes it: check the keys the message names"});
    }
  }
  return result;
}

// Reads the whole of path into *text. Empty when it did, else what went wrong and what to do:
// a directory, a device or a short read must not be taken for an empty file (which is valid
// TOML and would run on the defaults).
std::string ReadRegularFile(const std::string& path, std::string* text) {
  const char* const kCheckPath =
      " (check the path given to atlasd --config or --check-config, and that the user atlasd runs "
      "as may read it)";
  struct stat st;
  if (stat(path.c_str(), &st) != 0) {
    return "cannot open the configuration file: " + std::string(std::strerror(errno)) + kCheckPath;
  }
  if (S_ISDIR(st.st_mode)) {
    return "is a directory, not a configuration file (give the path of the TOML file itself, e.g. "
           "/etc/atlasd/atlasd.toml)";
  }
  if (!S_ISREG(st.st_mode)) {
    return "is not a regular file (a device, FIFO or socket), not a configuration file (give the "
           "path of the TOML file itself, e.g. /etc/atlasd/atlasd.toml)";
  }
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    return "cannot open the configuration file: " + std::string(std::strerror(errno)) + kCheckPath;
  }
  text->clear();
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n > 0) {
      text->append(buffer, static_cast<size_t>(n));
    } else if (n == 0) {
      break;
    } else if (errno != EINTR) {
      const std::string why = std::strerror(errno);
      close(fd);
      return "reading the configuration file failed after " + std::to_string(text->size()) +
             " bytes: " + why + "; nothing of it was used (check the file and its file system)";
    }
  }
  close(fd);
  return "";
}

}  // namespace

namespace config {

std::string CheckNonEmpty(const std::string& s) { return s.empty() ? "must not be empty" : ""; }

std::string CheckDevicePath(const std::string& s) {
  if (s.empty() || s[0] != '/') return "must be an absolute device path like /dev/ttyUSB0";
  return "";
}

std::string CheckCanInterface(const std::string& s) {
  if (s.rfind("unix:", 0) == 0) {
    return s.size() > 5 && s[5] == '/' ? "" : "unix: must be followed by an absolute socket path";
  }
  // IFNAMSIZ is 16 with the terminating NUL.
  if (s.empty() || s.size() > 15 || s.find_first_of("/ \t:") != std::string::npos) {
    return "must be a CAN interface name like can0 (at most 15 characters) or unix:PATH, got \"" +
           s + "\"";
  }
  return "";
}

std::string CheckLcmUrl(const std::string& s) {
  for (const char* scheme : {"udpm://", "memq://", "file://", "tcpq://"}) {
    if (s.rfind(scheme, 0) == 0) return "";
  }
  return "must be an LCM URL (udpm://, memq://, file:// or tcpq://), got \"" + s + "\"";
}

std::string CheckChannelName(const std::string& s) {
  if (s.empty() || s.size() > 63) return "must have 1 to 63 characters";
  for (char c : s) {
    if (c <= ' ' || c > '~') return "must be printable ASCII without spaces, got \"" + s + "\"";
  }
  return "";
}

std::string CheckAbsolutePath(const std::string& s) {
  return !s.empty() && s[0] == '/' ? "" : "must be an absolute path, got \"" + s + "\"";
}

namespace {

// The channels atlasd publishes on, by their key under lcm.channels.
std::array<std::pair<const char*, const std::string*>, 9> PublishedChannels(const LcmChannels& c) {
  return {{{"pose", &c.pose},
           {"reference_pose", &c.reference_pose},
           {"local_map", &c.local_map},
           {"graph", &c.graph},
           {"hypotheses", &c.hypotheses},
           {"health", &c.health},
           {"raw_odometry", &c.raw_odometry},
           {"raw_laser", &c.raw_laser},
           {"raw_sonar", &c.raw_sonar}}};
}

// input.source = "lcm": no device is opened; atlasd must not read what it publishes itself.
template <typename Read>
void CheckLcmInput(const DaemonOptions& o, const Read& read,
                   const std::function<void(const std::string&, const std::string&)>& report) {
  if (!read({"input.source"}) || o.input.source != InputSource::kLcm) return;
  if (read({"sonar.enabled"}) && o.sonar.enabled) {
    report("sonar.enabled",
           "input.source \"lcm\" reads no sonar (laser and odometry only): set sonar.enabled = "
           "false, or input.source = \"devices\"");
  }
  if (read({"input.laser_channel", "input.odometry_channel"}) &&
      o.input.laser_channel == o.input.odometry_channel) {
    report("input.odometry_channel", "is the same channel as input.laser_channel");
  }
  const auto published = PublishedChannels(o.lcm.channels);
  const std::pair<const char*, const std::string*> inputs[] = {
      {"input.laser_channel", &o.input.laser_channel},
      {"input.odometry_channel", &o.input.odometry_channel}};
  for (const auto& [key, name] : inputs) {
    for (const auto& [out, channel] : published) {
      const bool raw = std::string(out).rfind("raw_", 0) == 0;
      const std::string out_key = std::string("lcm.channels.") + out;
      if (!read({key, out_key}) || *name != *channel) continue;
      if (!raw) {
        report(key, std::string("is ") + out_key +
                        ", which atlasd publishes on: it would read its own messages; choose "
                        "another channel");
      } else if (read({"lcm.republish_raw"}) && o.lcm.republish_raw) {
        // Named at republish_raw, which the file sets (it is off by default).
        report("lcm.republish_raw", std::string("republishes what atlasd reads on ") + out_key +
                                        " (\"" + *channel + "\"), which is " + key +
                                        ": atlasd would read its own messages; set it to false "
                                        "or choose another " +
                                        key);
      }
    }
  }
}

}  // namespace

void CrossCheck(const DaemonOptions& o,
                const std::function<void(const std::string&, const std::string&)>& report,
                const std::function<bool(const std::string&)>& usable) {
  const auto read = [&](std::initializer_list<std::string> keys) {
    if (!usable) return true;
    for (const std::string& k : keys)
      if (!usable(k)) return false;
    return true;
  };
  if (read({"laser.angular_resolution_deg", "laser.angular_range_deg"}) &&
      o.laser.angular_resolution_deg < 0.5 && o.laser.angular_range_deg != 100) {
    report("laser.angular_resolution_deg", "0.25 degrees needs laser.angular_range_deg = 100");
  }
  if (read({"laser.unit", "laser.max_range_m"}) && o.laser.unit == sick::Unit::kMillimetre &&
      o.laser.max_range_m > 8.191) {
    report("laser.max_range_m", "with unit \"mm\" the scanner measures at most 8.191 m");
  }
  if (read({"sonar.enabled", "laser.enabled", "sonar.device", "laser.device"}) && o.sonar.enabled &&
      o.laser.enabled && o.sonar.device == o.laser.device) {
    report("sonar.device", "is the same device as laser.device");
  }
  if (read({"localmap.sensors", "sonar.enabled"}) && o.localmap.sensors != RangeSensors::kLaser &&
      !o.sonar.enabled) {
    report("localmap.sensors", "maps with the sonar: needs sonar.enabled = true");
  }
  if (read({"localmap.sensors", "laser.enabled"}) && o.localmap.sensors == RangeSensors::kBoth &&
      !o.laser.enabled) {
    report("localmap.sensors", "\"both\" maps with the laser too: needs laser.enabled = true");
  }
  if (read({"localmap.kind", "localmap.sensors"}) && o.localmap.kind == LocalMapKind::kGrid &&
      o.localmap.sensors != RangeSensors::kLaser) {
    report("localmap.kind", "\"grid\" maps with the laser alone: needs sensors = \"laser\"");
  }
  const bool realtime = o.scheduling.policy != SchedPolicy::kOther;
  const bool scheduling = read({"scheduling.policy", "scheduling.priority"});
  if (scheduling && realtime && o.scheduling.priority < 1) {
    report("scheduling.priority", "must be 1..99 with policy \"fifo\" or \"rr\"");
  } else if (scheduling && !realtime && o.scheduling.priority != 0) {
    report("scheduling.priority", "must be 0 with policy \"other\"");
  }
  std::set<int> cpus;
  for (int c : o.scheduling.cpu_affinity) {
    if (read({"scheduling.cpu_affinity"}) && !cpus.insert(c).second) {
      report("scheduling.cpu_affinity", "lists CPU " + std::to_string(c) + " twice");
    }
  }
  const auto channels = PublishedChannels(o.lcm.channels);
  for (size_t i = 0; i < std::size(channels); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (read({std::string("lcm.channels.") + channels[i].first,
                std::string("lcm.channels.") + channels[j].first}) &&
          *channels[i].second == *channels[j].second) {
        report(std::string("lcm.channels.") + channels[i].first,
               "is the same channel as lcm.channels." + std::string(channels[j].first));
      }
    }
  }
  CheckLcmInput(o, read, report);
}

}  // namespace config

std::string DaemonOptions::Validate() const {
  std::vector<std::string> problems;
  DaemonOptions copy = *this;  // the visitor takes mutable references; nothing is changed
  ValueChecker checker(&problems);
  config::VisitOptions(checker, copy);
  config::CrossCheck(*this, [&](const std::string& key, const std::string& message) {
    problems.push_back(key + ": " + message);
  });
  std::string out;
  for (const std::string& p : problems) out += (out.empty() ? "" : "\n") + p;
  return out;
}

std::map<std::string, std::string> FlattenOptions(const DaemonOptions& options) {
  DaemonOptions copy = options;  // the visitor takes mutable references; nothing is changed
  Flattener f;
  config::VisitOptions(f, copy);
  return std::move(f.values);
}

bool IsReloadableKey(const std::string& key) {
  for (const char* prefix :
       {"noise.", "atlas.", "lcm.republish_raw", "lcm.health_period_s", "lcm.graph_period_s",
        "lcm.local_map_period_s", "loop.step_budget_ms", "state.save_period_s"}) {
    if (key.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

ReloadDiff DiffForReload(const DaemonOptions& running, const DaemonOptions& loaded) {
  const auto a = FlattenOptions(running);
  const auto b = FlattenOptions(loaded);
  ReloadDiff diff;
  for (const auto& [key, value] : a) {
    if (b.at(key) == value) continue;
    (IsReloadableKey(key) ? diff.reloadable : diff.needs_restart).push_back(key);
  }
  return diff;
}

std::string ConfigError::ToString() const {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line) + ":" + std::to_string(column);
  s += ": ";
  if (!key.empty()) s += key + ": ";
  return s + message;
}

ConfigResult LoadConfigString(std::string_view toml_text, const std::string& source_name,
                              const DerivedCheck& derived) {
  try {
    const toml::table root = toml::parse(toml_text, source_name);
    return LoadFromTable(root, source_name, derived);
  } catch (const toml::parse_error& e) {
    ConfigResult result;
    result.errors.push_back(ConfigError{source_name, static_cast<int>(e.source().begin.line),
                                        static_cast<int>(e.source().begin.column), "",
                                        "not valid TOML: " + std::string(e.description())});
    return result;
  }
}

ConfigResult LoadConfigFile(const std::string& path, const DerivedCheck& derived) {
  std::string text;
  if (std::string problem = ReadRegularFile(path, &text); !problem.empty()) {
    ConfigResult result;
    result.errors.push_back(ConfigError{path, 0, 0, "", problem});
    return result;
  }
  return LoadConfigString(text, path, derived);
}

int CheckConfigCommand(const std::string& path, const DerivedCheck& derived, std::ostream& out,
                       std::ostream& err) {
  const ConfigResult r = LoadConfigFile(path, derived);
  if (!r.ok()) {
    for (const ConfigError& e : r.errors) err << e.ToString() << "\n";
    err << path << ": " << r.errors.size() << " error(s); see config/atlasd.toml for every key\n";
    return kExitConfigError;
  }
  out << path << ": configuration is valid\n";
  return 0;
}

}  // namespace atlas
