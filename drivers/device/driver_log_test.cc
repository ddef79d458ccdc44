#include "drivers/device/driver_log.h"

#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

namespace atlas {

void PrintTo(const DriverLogLine& l, std::ostream* os) {
  *os << "<" << static_cast<int>(l.priority) << ">" << l.text;
}

namespace {

DriverLogLine L(LogPriority p, std::string text) { return {p, std::move(text)}; }

TEST(DriverLogTest, AMissingDeviceIsSaidOncePerReasonNotOncePerRetry) {
  DriverLog log("laser /dev/ttyUSB0");
  EXPECT_EQ(log.Connecting(), L(LogPriority::kInfo, "laser /dev/ttyUSB0: connecting"));
  const std::string enoent = "serial /dev/ttyUSB0: No such file or directory (ENOENT)";
  EXPECT_EQ(log.AttemptFailed(enoent),
            L(LogPriority::kErr, "laser /dev/ttyUSB0: " + enoent + "; retrying"));
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(log.Connecting(), std::nullopt);
    EXPECT_EQ(log.AttemptFailed(enoent), std::nullopt);
  }
  // Another reason is said, once.
  const std::string enotty = "serial /dev/ttyUSB0: not a terminal (ENOTTY)";
  EXPECT_EQ(log.AttemptFailed(enotty)->text, "laser /dev/ttyUSB0: " + enotty + "; retrying");
  EXPECT_EQ(log.AttemptFailed(enotty), std::nullopt);
  EXPECT_EQ(log.Delivering(),
            L(LogPriority::kNotice, "laser /dev/ttyUSB0: running after 23 failed attempts"));
  EXPECT_EQ(log.Delivering(), std::nullopt);  // once per session
}

TEST(DriverLogTest, ALostDeviceIsAWarningAndTheSameFailureIsSaidAgainAfterItRan) {
  DriverLog log("laser /dev/ttyUSB0");
  log.Connecting();
  EXPECT_EQ(log.Delivering(), L(LogPriority::kNotice, "laser /dev/ttyUSB0: running"));
  EXPECT_EQ(log.Lost("serial /dev/ttyUSB0: device went away (EOF)"),
            L(LogPriority::kWarning,
              "laser /dev/ttyUSB0: lost (serial /dev/ttyUSB0: device went away (EOF)); "
              "reconnecting"));
  const std::string enoent = "serial /dev/ttyUSB0: No such file or directory (ENOENT)";
  ASSERT_TRUE(log.AttemptFailed(enoent).has_value());
  EXPECT_EQ(log.AttemptFailed(enoent), std::nullopt);
  EXPECT_EQ(log.Delivering()->text, "laser /dev/ttyUSB0: running after 2 failed attempts");
  log.Lost("EOF");
  EXPECT_TRUE(log.AttemptFailed(enoent).has_value());  // a new outage
}

// SocketCAN on a down interface opens and dies at once: each session ends before a message,
// which is a failed attempt, not a loss: one line, not two per retry.
TEST(DriverLogTest, SessionsThatDieBeforeTheirFirstMessageAreFailedAttempts) {
  DriverLog log("odometry can0");
  log.Connecting();
  const std::string down = "CAN can0: interface is down (ENETDOWN)";
  EXPECT_EQ(log.Lost(down), L(LogPriority::kErr, "odometry can0: " + down + "; retrying"));
  for (int i = 0; i < 10; ++i) EXPECT_EQ(log.Lost(down), std::nullopt);
  EXPECT_EQ(log.Stalled("no data for 1.00 s"), std::nullopt);  // not delivering: no stall
}

TEST(DriverLogTest, StallAndResumeAreSaidOncePerSilence) {
  DriverLog log("sonar /dev/ttyACM0");
  log.Connecting();
  log.Delivering();
  EXPECT_EQ(log.Resumed(), std::nullopt);
  EXPECT_EQ(log.Stalled("no data for 1.00 s"),
            L(LogPriority::kWarning, "sonar /dev/ttyACM0: stalled: no data for 1.00 s"));
  EXPECT_EQ(log.Stalled("no data for 1.00 s"), std::nullopt);
  EXPECT_EQ(log.Resumed(), L(LogPriority::kNotice, "sonar /dev/ttyACM0: data again"));
  EXPECT_EQ(log.Resumed(), std::nullopt);
  EXPECT_TRUE(log.Stalled("no data for 1.00 s").has_value());
}

TEST(DriverLogTest, ConditionsAreSaidWhenTheyChange) {
  DriverLog log("laser /dev/ttyUSB0");
  EXPECT_EQ(log.Condition(LogPriority::kWarning, "scans in mm, laser.unit says cm"),
            L(LogPriority::kWarning, "laser /dev/ttyUSB0: scans in mm, laser.unit says cm"));
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(log.Condition(LogPriority::kWarning, "scans in mm, laser.unit says cm"),
              std::nullopt);
  EXPECT_TRUE(log.Condition(LogPriority::kWarning, "scanner status 0x05").has_value());
}

TEST(DriverLogTest, GivingUpIsAnErrorAndStoppingIsInfo) {
  DriverLog log("odometry unix:/x");
  EXPECT_EQ(
      log.GaveUp("no such socket (3 attempts)"),
      L(LogPriority::kErr, "odometry unix:/x: failed: no such socket (3 attempts); giving up"));
  EXPECT_EQ(log.Stopped(), L(LogPriority::kInfo, "odometry unix:/x: stopped"));
}

}  // namespace
}  // namespace atlas
