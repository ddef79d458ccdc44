#include "drivers/can/can_transport.h"

#include <gtest/gtest.h>
#include <linux/can.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <thread>

namespace atlas {
namespace {

TEST(CanTransportTest, SocketCanOnAKernelWithoutCanSaysSoPlainly) {
  // Whether this kernel has CAN is asked of the kernel, not of the code under test.
  const int probe = socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (probe >= 0) {
    close(probe);
    GTEST_SKIP() << "this kernel has CAN support";
  }
  ASSERT_EQ(errno, EAFNOSUPPORT) << std::strerror(errno);
  auto t = MakeCanTransport("can0");
  std::string err;
  ASSERT_FALSE(t->Open(&err));
  EXPECT_NE(err.find("EAFNOSUPPORT"), std::string::npos) << err;
  EXPECT_NE(err.find("this kernel has no CAN support"), std::string::npos) << err;
  EXPECT_NE(err.find("can0"), std::string::npos) << err;
}

TEST(CanTransportTest, ErrnoTextsForTheInterfaceProblems) {
  EXPECT_NE(CanErrnoText("can0", ENODEV).find("no such interface (ENODEV)"), std::string::npos);
  EXPECT_NE(CanErrnoText("can0", ENETDOWN).find("is down (ENETDOWN)"), std::string::npos);
  EXPECT_NE(CanErrnoText("can0", ENETDOWN).find("ip link set can0 up"), std::string::npos);
}

// As candump: a down interface is waited for on the same socket (it stays bound and frames come
// again once the interface is up); only a removed interface needs a reopen.
TEST(CanTransportTest, ReadErrnosThatKeepTheSocketAndThatDoNot) {
  EXPECT_EQ(CanReadStatusForErrno(ENETDOWN), CanRead::kNetDown);
  EXPECT_EQ(CanReadStatusForErrno(ENODEV), CanRead::kGone);
  EXPECT_EQ(CanReadStatusForErrno(ENXIO), CanRead::kGone);
  EXPECT_EQ(CanReadStatusForErrno(EIO), CanRead::kError);
}

TEST(CanTransportTest, FakeBusWithNobodyListening) {
  auto t = MakeCanTransport("unix:/nonexistent/atlas_bus");
  std::string err;
  EXPECT_FALSE(t->Open(&err));
  EXPECT_NE(err.find("nobody is listening"), std::string::npos) << err;
  EXPECT_NE(err.find("unix:/nonexistent/atlas_bus"), std::string::npos) << err;
  // The hint names atlas-fakedev's real option and the socket path without the scheme.
  EXPECT_NE(err.find("atlas-fakedev --can-socket /nonexistent/atlas_bus)"), std::string::npos)
      << err;
}

// A bare SOCK_SEQPACKET listener: frames arrive whole, odd-sized datagrams are rejected, and the
// listener going away is kGone.
TEST(CanTransportTest, FakeBusDatagrams) {
  char dir[] = "/tmp/atlas_can_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string path = std::string(dir) + "/bus";
  const int srv = socket(AF_UNIX, SOCK_SEQPACKET, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  strcpy(addr.sun_path, path.c_str());
  ASSERT_EQ(bind(srv, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
  ASSERT_EQ(listen(srv, 4), 0);

  auto t = MakeCanTransport("unix:" + path);
  std::string err;
  ASSERT_TRUE(t->Open(&err)) << err;
  const int peer = accept(srv, nullptr, nullptr);
  ASSERT_GE(peer, 0);
  EXPECT_EQ(t->Read(10).status, CanRead::kTimeout);

  struct can_frame f {};
  f.can_id = 0x311;
  f.can_dlc = 8;
  const uint8_t payload[8] = {0x00, 0x00, 0x03, 0xE8, 0xFF, 0xFF, 0xFF, 0xFE};
  memcpy(f.data, payload, 8);
  ASSERT_EQ(send(peer, &f, sizeof(f), 0), 16);
  CanReadResult r = t->Read(500);
  ASSERT_EQ(r.status, CanRead::kFrame) << r.error;
  EXPECT_EQ(r.frame.id, 0x311u);
  EXPECT_EQ(r.frame.dlc, 8);
  EXPECT_EQ(memcmp(r.frame.data.data(), payload, 8), 0);

  // The stamp is the kernel's arrival, not the time of the read: a frame read 30 ms after it
  // came is stamped before the read (the 1 ms is for mapping the real-time stamp).
  const Time before_send = Now();
  ASSERT_EQ(send(peer, &f, sizeof(f), 0), 16);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  const Time before_read = Now();
  r = t->Read(500);
  ASSERT_EQ(r.status, CanRead::kFrame) << r.error;
  EXPECT_TRUE(r.kernel_stamp);
  EXPECT_LT(r.stamp, before_read);
  EXPECT_GE(r.stamp, before_send - std::chrono::milliseconds(1));

  ASSERT_EQ(send(peer, payload, 5, 0), 5);
  EXPECT_EQ(t->Read(500).status, CanRead::kBadFrame);
  uint8_t big[40] = {};
  ASSERT_EQ(send(peer, big, sizeof(big), 0), 40);
  EXPECT_EQ(t->Read(500).status, CanRead::kBadFrame);

  CanFrame out;
  out.id = 0x221;
  out.dlc = 8;
  ASSERT_TRUE(t->Write(out, &err)) << err;
  struct can_frame in {};
  ASSERT_EQ(recv(peer, &in, sizeof(in), 0), 16);
  EXPECT_EQ(in.can_id, 0x221u);

  close(peer);
  EXPECT_EQ(t->Read(500).status, CanRead::kGone);
  close(srv);
  unlink(path.c_str());
  rmdir(dir);
}

}  // namespace
}  // namespace atlas
