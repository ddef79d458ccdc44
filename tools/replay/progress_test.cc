#include "tools/replay/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

namespace atlas {
namespace {

TEST(Progress, PercentRateAndTimeLeft) {
  EXPECT_EQ(FormatProgress("reading", 12.3e6, 27.1e6, 1.5, "MB", 1e6),
            "reading 45.4% (12.3 of 27.1 MB), 8.2 MB/s, 2 s left");
  EXPECT_EQ(FormatProgress("replaying", 4000, 10000, 5, "scans", 1),
            "replaying 40.0% (4000 of 10000 scans), 800 scans/s, 8 s left");
  // Done: no time left.
  EXPECT_EQ(FormatProgress("replaying", 10000, 10000, 20, "scans", 1),
            "replaying 100.0% (10000 of 10000 scans), 500 scans/s");
}

TEST(Progress, NothingToEstimateFromIsLeftOut) {
  // At the start: no rate, no time left.
  EXPECT_EQ(FormatProgress("reading", 0, 27.1e6, 0, "MB", 1e6), "reading 0.0% (0.0 of 27.1 MB)");
  // An unknown total (a pipe): the amount and the rate.
  EXPECT_EQ(FormatProgress("reading", 3e6, 0, 2, "MB", 1e6), "reading 3.0 MB, 1.5 MB/s");
  // More than the total (a growing file) stays at 100%.
  EXPECT_EQ(FormatProgress("reading", 11, 10, 1, "scans", 1),
            "reading 100.0% (11 of 10 scans), 11 scans/s");
}

TEST(Progress, DurationsReadAsMinutesAndHours) {
  EXPECT_EQ(FormatDuration(0.4), "0 s");
  EXPECT_EQ(FormatDuration(59.4), "59 s");
  EXPECT_EQ(FormatDuration(185), "3 min 05 s");
  EXPECT_EQ(FormatDuration(7800), "2 h 10 min");
  EXPECT_EQ(FormatDuration(-3), "0 s");
}

// What `write` prints on a stream.
std::string Printed(const std::function<void(std::FILE*)>& write) {
  char* text = nullptr;
  size_t size = 0;
  std::FILE* out = open_memstream(&text, &size);
  if (out == nullptr) return "open_memstream failed";
  write(out);
  std::fclose(out);
  std::string s(text, size);
  std::free(text);
  return s;
}

// On a terminal: one line rewritten in place, ended once; elsewhere plain lines.
TEST(Progress, ATerminalGetsOneLineRewrittenInPlace) {
  const std::string s = Printed([](std::FILE* out) {
    ProgressMeter meter(out, "atlas-replay", /*tty=*/true, std::chrono::hours(1));
    meter.Begin("replaying", "scans", 1);
    meter.Update(10, 10);  // the last update of a step is always shown
  });
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.substr(0, 1), "\r");
  EXPECT_NE(s.find("atlas-replay: replaying 100.0% (10 of 10 scans)"), std::string::npos) << s;
  EXPECT_EQ(s.find('\n'), s.size() - 1);
}

// The last update before Finish is shown on a terminal even when the rate limit held it back.
TEST(Progress, ATerminalShowsTheLastUpdateAtTheEnd) {
  const std::string s = Printed([](std::FILE* out) {
    ProgressMeter meter(out, "atlas-replay", /*tty=*/true, std::chrono::hours(1));
    meter.Begin("replaying", "scans", 1);
    for (int i = 1; i <= 99; ++i) meter.Update(i, 100);
  });
  EXPECT_NE(s.find("replaying 99.0% (99 of 100 scans)"), std::string::npos) << s;
  EXPECT_EQ(s.back(), '\n');
}

TEST(Progress, ElsewherePlainLinesEveryPeriodOnly) {
  EXPECT_EQ(Printed([](std::FILE* out) {
              ProgressMeter meter(out, "atlas-replay", /*tty=*/false, std::chrono::hours(1));
              meter.Begin("replaying", "scans", 1);
              for (int i = 1; i <= 100; ++i) meter.Update(i, 100);  // within the period
            }),
            "");
  const std::string s = Printed([](std::FILE* out) {
    ProgressMeter meter(out, "atlas-replay", /*tty=*/false, std::chrono::seconds(0));
    meter.Begin("reading", "MB", 1e6);
    meter.Update(1e6, 4e6);
    meter.Update(2e6, 4e6);
  });
  EXPECT_EQ(s.find('\r'), std::string::npos) << s;
  EXPECT_NE(s.find("atlas-replay: reading 25.0% (1.0 of 4.0 MB)"), std::string::npos) << s;
  EXPECT_NE(s.find("\natlas-replay: reading 50.0% (2.0 of 4.0 MB)"), std::string::npos) << s;
}

}  // namespace
}  // namespace atlas
