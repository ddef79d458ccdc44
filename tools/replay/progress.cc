#include "tools/replay/progress.h"

#include <algorithm>
#include <cmath>

namespace atlas {
namespace {

std::string Amount(double v, double scale) {
  char b[32];
  if (scale == 1)
    std::snprintf(b, sizeof(b), "%.0f", v);
  else
    std::snprintf(b, sizeof(b), "%.1f", v / scale);
  return b;
}

}  // namespace

std::string FormatDuration(double seconds) {
  const long long s = std::llround(std::max(0.0, seconds));
  char b[48];
  if (s < 60)
    std::snprintf(b, sizeof(b), "%lld s", s);
  else if (s < 3600)
    std::snprintf(b, sizeof(b), "%lld min %02lld s", s / 60, s % 60);
  else
    std::snprintf(b, sizeof(b), "%lld h %02lld min", s / 3600, (s % 3600) / 60);
  return b;
}

std::string FormatProgress(std::string_view what, double done, double total, double elapsed_s,
                           std::string_view unit, double scale) {
  std::string line(what);
  const std::string u(unit);
  if (total > 0) {
    char b[32];
    std::snprintf(b, sizeof(b), " %.1f%%", 100.0 * std::min(1.0, done / total));
    line += b;
    line += " (" + Amount(done, scale) + " of " + Amount(total, scale) + " " + u + ")";
  } else {
    line += " " + Amount(done, scale) + " " + u;
  }
  if (elapsed_s > 0 && done > 0) {
    const double rate = done / elapsed_s;
    line += ", " + Amount(rate, scale) + " " + u + "/s";
    if (total > done) line += ", " + FormatDuration((total - done) / rate) + " left";
  }
  return line;
}

ProgressMeter::ProgressMeter(std::FILE* out, std::string tool, bool tty,
                             Clock::duration plain_period)
    : out_(out), tool_(std::move(tool)), tty_(tty), plain_period_(plain_period) {}

void ProgressMeter::Begin(std::string what, std::string unit, double scale) {
  Finish();
  what_ = std::move(what);
  unit_ = std::move(unit);
  scale_ = scale;
  start_ = last_ = Clock::now();
}

void ProgressMeter::Update(double done, double total) {
  if (out_ == nullptr) return;
  const Clock::time_point now = Clock::now();
  const Clock::duration period = tty_ ? std::chrono::milliseconds(200) : plain_period_;
  const bool last = total > 0 && done >= total;
  done_ = done;
  total_ = total;
  held_ = true;
  if (now - last_ < period && !(last && tty_)) return;
  last_ = now;
  Print(done, total, now);
}

void ProgressMeter::Print(double done, double total, Clock::time_point now) {
  const std::string text =
      tool_ + ": " +
      FormatProgress(what_, done, total, std::chrono::duration<double>(now - start_).count(), unit_,
                     scale_);
  if (tty_) {
    // Over the previous line, blanking what is left of a longer one.
    std::fprintf(out_, "\r%s%*s", text.c_str(),
                 static_cast<int>(shown_ > text.size() ? shown_ - text.size() : 0), "");
    shown_ = text.size();
  } else {
    std::fprintf(out_, "%s\n", text.c_str());
  }
  std::fflush(out_);
  printed_ = true;
  held_ = false;
}

void ProgressMeter::Finish() {
  if (out_ != nullptr && tty_ && held_) Print(done_, total_, Clock::now());
  if (out_ != nullptr && tty_ && printed_) std::fputc('\n', out_);
  printed_ = held_ = false;
  shown_ = 0;
}

}  // namespace atlas
