#pragma once
// Progress of atlas-replay's long steps on stderr (reading the log, replaying it). On a
// terminal: one line rewritten in place ('\r') with the percentage, the rate and the time left.
// Elsewhere (a file, a pipe, the journal): a plain line every plain_period, so that a log of a
// long run stays short. Reading's percentage is of the log file's bytes (compressed bytes of a
// .gz), replaying's of the scans.

#include <chrono>
#include <cstdio>
#include <string>
#include <string_view>

namespace atlas {

// "reading 45.2% (12.3 of 27.1 MB), 8.1 MB/s, 2 s left": `done` and `total` in the unit's base
// (bytes, scans), shown divided by `scale` (1e6 for MB; 1 shows integers). No percentage when
// total <= 0, no rate and time left before any time has passed or anything was done.
std::string FormatProgress(std::string_view what, double done, double total, double elapsed_s,
                           std::string_view unit, double scale);

// "7 s", "3 min 05 s", "2 h 10 min".
std::string FormatDuration(double seconds);

class ProgressMeter {
 public:
  using Clock = std::chrono::steady_clock;
  // `out` null: says nothing (--quiet).
  ProgressMeter(std::FILE* out, std::string tool, bool tty,
                Clock::duration plain_period = std::chrono::seconds(10));
  ~ProgressMeter() { Finish(); }
  // A new step: its name and unit; the clock starts now.
  void Begin(std::string what, std::string unit, double scale);
  // Prints when due: on a terminal at most 5 times a second, else every plain_period; the
  // last update of a step (done >= total) is always shown.
  void Update(double done, double total);
  // Ends the terminal's line, after showing the last update if it was held back.
  void Finish();

 private:
  void Print(double done, double total, Clock::time_point now);

  std::FILE* out_;
  std::string tool_, what_, unit_;
  bool tty_;
  Clock::duration plain_period_;
  double scale_ = 1;
  Clock::time_point start_, last_;
  size_t shown_ = 0;  // length of the line on the terminal
  bool printed_ = false;
  bool held_ = false;  // an update not shown yet
  double done_ = 0, total_ = 0;
};

}  // namespace atlas
