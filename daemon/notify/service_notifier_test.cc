#include "daemon/notify/service_notifier.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace atlas {
namespace {

// A fake systemd: a Unix datagram socket bound in a temporary directory, named by
// $NOTIFY_SOCKET, from which the test reads what the notifier sent.
class FakeNotifySocket : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = testing::TempDir() + "atlas_notify_" + std::to_string(getpid());
    unlink(path_.c_str());
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ASSERT_GE(fd_, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    ASSERT_LT(path_.size(), sizeof(addr.sun_path));
    path_.copy(addr.sun_path, path_.size());
    ASSERT_EQ(bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    timeval timeout{2, 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
    setenv("NOTIFY_SOCKET", path_.c_str(), 1);
  }

  void TearDown() override {
    unsetenv("NOTIFY_SOCKET");
    unsetenv("WATCHDOG_USEC");
    unsetenv("WATCHDOG_PID");
    if (fd_ >= 0) close(fd_);
    unlink(path_.c_str());
  }

  // The next datagram, or "" after a 2 s timeout.
  std::string Receive() {
    char buf[4096];
    const ssize_t n = recv(fd_, buf, sizeof(buf), 0);
    return n > 0 ? std::string(buf, static_cast<size_t>(n)) : std::string();
  }

  std::string path_;
  int fd_ = -1;
};

TEST_F(FakeNotifySocket, ReceivesTheLifecycleInOrder) {
  ServiceNotifier n;
  EXPECT_EQ(n.Status("opening devices"), NotifyResult::kSent);
  EXPECT_EQ(n.Ready(), NotifyResult::kSent);
  EXPECT_EQ(n.Watchdog(), NotifyResult::kSent);
  EXPECT_EQ(n.Status("step 3 ms, 12 frames"), NotifyResult::kSent);
  EXPECT_EQ(n.Watchdog(), NotifyResult::kSent);
  EXPECT_EQ(n.Stopping(), NotifyResult::kSent);
  EXPECT_EQ(Receive(), "STATUS=opening devices");
  EXPECT_EQ(Receive(), "READY=1");
  EXPECT_EQ(Receive(), "WATCHDOG=1");
  EXPECT_EQ(Receive(), "STATUS=step 3 ms, 12 frames");
  EXPECT_EQ(Receive(), "WATCHDOG=1");
  EXPECT_EQ(Receive(), "STOPPING=1");
}

TEST_F(FakeNotifySocket, StatusIsKeptOnOneLine) {
  ServiceNotifier n;
  EXPECT_EQ(n.Status("a\nREADY=1\r"), NotifyResult::kSent);
  EXPECT_EQ(Receive(), "STATUS=a READY=1 ");
}

TEST_F(FakeNotifySocket, ExtendTimeoutSaysHowLongFromNow) {
  ServiceNotifier n;
  EXPECT_EQ(n.ExtendTimeout(std::chrono::seconds(30)), NotifyResult::kSent);
  EXPECT_EQ(Receive(), "EXTEND_TIMEOUT_USEC=30000000");
}

TEST_F(FakeNotifySocket, WatchdogIntervalIsReadForThisProcessOnly) {
  EXPECT_EQ(ServiceNotifier::WatchdogInterval().count(), 0);
  setenv("WATCHDOG_USEC", "3000000", 1);
  setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
  EXPECT_EQ(ServiceNotifier::WatchdogInterval().count(), 3000000);
  setenv("WATCHDOG_PID", std::to_string(getpid() + 1).c_str(), 1);
  EXPECT_EQ(ServiceNotifier::WatchdogInterval().count(), 0);
}

TEST(ServiceNotifier, OutsideSystemdNothingIsSent) {
  unsetenv("NOTIFY_SOCKET");
  ServiceNotifier n;
  EXPECT_EQ(n.Ready(), NotifyResult::kNotUnderSystemd);
  EXPECT_EQ(n.Watchdog(), NotifyResult::kNotUnderSystemd);
}

TEST(ServiceNotifier, ASocketNobodyListensOnIsAFailure) {
  setenv("NOTIFY_SOCKET", "/nonexistent/atlas_notify", 1);
  ServiceNotifier n;
  EXPECT_EQ(n.Ready(), NotifyResult::kFailed);
  unsetenv("NOTIFY_SOCKET");
}

}  // namespace
}  // namespace atlas
