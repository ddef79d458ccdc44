#include "drivers/serial/serial_port.h"

#include <errno.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "drivers/serial/pseudo_terminal.h"

namespace atlas {
namespace {

TEST(SerialPortTest, ValidatesOptions) {
  SerialOptions o;
  EXPECT_NE(o.Validate(), "");
  o.device = "/dev/ttyS0";
  EXPECT_EQ(o.Validate(), "");
  o.baud = 12345;
  EXPECT_NE(o.Validate().find("unsupported baud rate 12345"), std::string::npos);
  o.baud = 500000;
  EXPECT_EQ(o.Validate(), "");
}

TEST(SerialPortTest, MissingDeviceNamesPathAndErrno) {
  SerialPort port;
  std::string err;
  EXPECT_FALSE(port.Open({"/nonexistent/ttyLMS", 9600, true}, &err));
  EXPECT_NE(err.find("/nonexistent/ttyLMS"), std::string::npos) << err;
  EXPECT_NE(err.find("ENOENT"), std::string::npos) << err;
}

TEST(SerialPortTest, PermissionDeniedMentionsDialout) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  ASSERT_EQ(chmod(pty.slave_path().c_str(), 0600), 0);
  // As root permissions are not enforced: try from a child that drops to "nobody".
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) _exit(2);
    if (geteuid() != 0 && chmod(pty.slave_path().c_str(), 0) != 0) _exit(2);
    SerialPort port;
    std::string e;
    const bool opened = port.Open({pty.slave_path(), 9600, true}, &e);
    _exit(!opened && e.find("dialout") != std::string::npos && e.find("EACCES") != std::string::npos
              ? 0
              : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 2) GTEST_SKIP() << "cannot drop privileges here (no CAP_SETUID)";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "the error did not say EACCES and dialout";
}

TEST(SerialPortTest, ErrnoTextsSayWhatToDo) {
  EXPECT_NE(SerialErrnoText("/dev/ttyS3", EACCES).find("dialout group"), std::string::npos);
  EXPECT_NE(SerialErrnoText("/dev/ttyS3", EACCES).find("/dev/ttyS3"), std::string::npos);
  EXPECT_NE(SerialErrnoText("/dev/ttyS3", EBUSY).find("busy (EBUSY)"), std::string::npos);
  EXPECT_NE(SerialErrnoText("/dev/ttyS3", ENOENT).find("ENOENT"), std::string::npos);
  EXPECT_NE(SerialErrnoText("/dev/ttyS3", EIO).find("errno 5"), std::string::npos);
}

TEST(SerialPortTest, NotATerminalIsRefused) {
  SerialPort port;
  std::string err;
  EXPECT_FALSE(port.Open({"/dev/null", 9600, true}, &err));
  EXPECT_NE(err.find("ENOTTY"), std::string::npos) << err;
}

TEST(SerialPortTest, SecondExclusiveOpenIsBusy) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  SerialPort a, b;
  ASSERT_TRUE(a.Open({pty.slave_path(), 9600, true}, &err)) << err;
  EXPECT_FALSE(b.Open({pty.slave_path(), 9600, true}, &err));
  EXPECT_NE(err.find("busy"), std::string::npos) << err;
  EXPECT_NE(err.find(pty.slave_path()), std::string::npos) << err;
  a.Close();
  EXPECT_TRUE(b.Open({pty.slave_path(), 9600, true}, &err)) << err;
}

TEST(SerialPortTest, RawBytesBothWaysAndTimeout) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  SerialPort port;
  ASSERT_TRUE(port.Open({pty.slave_path(), 9600, true}, &err)) << err;
  uint8_t buf[64];
  EXPECT_EQ(port.Read(buf, sizeof(buf), 20).status, SerialIo::kTimeout);
  // Bytes a cooked terminal would mangle: CR, NL, XON/XOFF, ^C, 0xFF.
  const std::vector<uint8_t> out = {0x02, 0x0d, 0x0a, 0x11, 0x13, 0x03, 0xff, 0x00};
  ASSERT_TRUE(pty.WriteAll(out.data(), out.size()));
  std::vector<uint8_t> got;
  while (got.size() < out.size()) {
    SerialResult r = port.Read(buf, sizeof(buf), 500);
    ASSERT_EQ(r.status, SerialIo::kData);
    got.insert(got.end(), buf, buf + r.n);
  }
  EXPECT_EQ(got, out);
  ASSERT_EQ(port.WriteAll(out.data(), out.size(), 500).status, SerialIo::kData);
  got.clear();
  while (got.size() < out.size()) {
    long n = pty.Read(buf, sizeof(buf), 500);
    ASSERT_GT(n, 0);
    got.insert(got.end(), buf, buf + n);
  }
  EXPECT_EQ(got, out);
}

// A signal that interrupts the wait (poll's EINTR) is not the timeout: the read waits on and
// returns the byte that comes after it.
TEST(SerialPortTest, ASignalDoesNotEndTheWait) {
  struct sigaction quiet {};
  quiet.sa_handler = [](int) {};
  sigemptyset(&quiet.sa_mask);
  quiet.sa_flags = 0;  // no SA_RESTART: poll() returns EINTR
  struct sigaction before {};
  ASSERT_EQ(sigaction(SIGUSR2, &quiet, &before), 0);
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  SerialPort port;
  ASSERT_TRUE(port.Open({pty.slave_path(), 9600, true}, &err)) << err;
  std::atomic<bool> reading{false};
  SerialResult r;
  std::thread reader([&] {
    uint8_t buf[8];
    reading = true;
    r = port.Read(buf, sizeof buf, 20000);
  });
  while (!reading) std::this_thread::yield();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let it block in poll()
  ASSERT_EQ(pthread_kill(reader.native_handle(), SIGUSR2), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const uint8_t byte = 0x42;
  ASSERT_TRUE(pty.WriteAll(&byte, 1));
  reader.join();
  sigaction(SIGUSR2, &before, nullptr);
  EXPECT_EQ(r.status, SerialIo::kData) << r.error;
  EXPECT_EQ(r.n, 1u);
}

TEST(SerialPortTest, ReopenChangesTheRateIncluding500k) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  SerialPort port;
  ASSERT_TRUE(port.Open({pty.slave_path(), 9600, true}, &err)) << err;
  EXPECT_EQ(pty.SlaveBaud(), 9600);
  ASSERT_TRUE(port.Reopen(500000, &err)) << err;
  EXPECT_EQ(port.baud(), 500000);
  EXPECT_EQ(pty.SlaveBaud(), 500000);
  ASSERT_TRUE(port.Reopen(38400, &err)) << err;
  EXPECT_EQ(pty.SlaveBaud(), 38400);
}

TEST(SerialPortTest, MasterClosedIsReportedAsGone) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  SerialPort port;
  ASSERT_TRUE(port.Open({pty.slave_path(), 9600, true}, &err)) << err;
  pty.Close();
  uint8_t buf[16];
  SerialResult r = port.Read(buf, sizeof(buf), 500);
  EXPECT_EQ(r.status, SerialIo::kGone) << r.error;
  EXPECT_NE(r.error.find(port.device()), std::string::npos);
}

TEST(SerialPortTest, SymlinkIsRepointedWhenRecreated) {
  char dir[] = "/tmp/atlas_serial_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string link = std::string(dir) + "/laser";
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create(link, &err)) << err;
  pty.Close();
  EXPECT_NE(access(link.c_str(), F_OK), 0);
  ASSERT_TRUE(pty.Create(link, &err)) << err;
  // The link names the new pseudo-terminal (its number may be the old one's, reused).
  char target[256] = {};
  ASSERT_GT(readlink(link.c_str(), target, sizeof target - 1), 0);
  EXPECT_EQ(std::string(target), pty.slave_path());
  SerialPort port;
  ASSERT_TRUE(port.Open({link, 9600, true}, &err)) << err;
  pty.Close();
  port.Close();
  rmdir(dir);
}

}  // namespace
}  // namespace atlas
