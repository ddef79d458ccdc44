#include "daemon/notify/stderr_log.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace atlas {
namespace {

TEST(StderrLogTest, TheJournalGetsTheSdDaemonPrefix) {
  EXPECT_EQ(StderrLogLine(LogPriority::kErr, "laser /dev/ttyUSB0: ENOENT", true),
            "<3>atlasd: laser /dev/ttyUSB0: ENOENT\n");
  EXPECT_EQ(StderrLogLine(LogPriority::kWarning, "w", true), "<4>atlasd: w\n");
  EXPECT_EQ(StderrLogLine(LogPriority::kNotice, "n", true), "<5>atlasd: n\n");
  EXPECT_EQ(StderrLogLine(LogPriority::kInfo, "i", true), "<6>atlasd: i\n");
  EXPECT_EQ(StderrLogLine(LogPriority::kDebug, "d", true), "<7>atlasd: d\n");
}

TEST(StderrLogTest, ATerminalGetsWordsAndEveryMessageIsOneLine) {
  EXPECT_EQ(StderrLogLine(LogPriority::kErr, "e", false), "atlasd: error: e\n");
  EXPECT_EQ(StderrLogLine(LogPriority::kWarning, "w", false), "atlasd: warning: w\n");
  EXPECT_EQ(StderrLogLine(LogPriority::kNotice, "n", false), "atlasd: n\n");
  // A reason with a newline (a device's text) cannot start a line with another priority.
  EXPECT_EQ(StderrLogLine(LogPriority::kNotice, "a\n<3>b", true), "<5>atlasd: a <3>b\n");
}

TEST(StderrLogTest, StderrIsTheJournalOnlyWhenJournalStreamNamesIt) {
  struct stat st {};
  ASSERT_EQ(fstat(STDERR_FILENO, &st), 0);
  const std::string mine = std::to_string(static_cast<unsigned long long>(st.st_dev)) + ":" +
                           std::to_string(static_cast<unsigned long long>(st.st_ino));
  unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(StderrIsJournal());
  setenv("JOURNAL_STREAM", mine.c_str(), 1);
  EXPECT_TRUE(StderrIsJournal());
  // Inherited from a parent whose stderr was the journal, while ours is redirected.
  setenv("JOURNAL_STREAM", (mine + "1").c_str(), 1);
  EXPECT_FALSE(StderrIsJournal());
  setenv("JOURNAL_STREAM", "garbage", 1);
  EXPECT_FALSE(StderrIsJournal());
  unsetenv("JOURNAL_STREAM");
}

}  // namespace
}  // namespace atlas
