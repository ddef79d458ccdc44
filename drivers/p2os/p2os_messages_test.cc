#include "drivers/p2os/p2os_messages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <numbers>
#include <vector>

namespace atlas::p2os {
namespace {

using Bytes = std::vector<uint8_t>;

// Parses a whole packet whose bytes stay alive for the rest of the test program.
PacketView Parsed(const Bytes& whole) {
  static std::deque<Bytes> kept;
  kept.push_back(whole);
  PacketView v;
  EXPECT_EQ(ParsePacket(kept.back(), &v), PacketParse::kOk);
  return v;
}

void PutU16(Bytes* b, uint16_t v) {
  b->push_back(static_cast<uint8_t>(v & 0xFF));
  b->push_back(static_cast<uint8_t>(v >> 8));
}

// A standard SIP payload built by hand from the spec's field list.
Bytes HandSip(const std::vector<std::pair<uint8_t, uint16_t>>& sonars) {
  Bytes p{0x33};
  PutU16(&p, 0x1234);  // xpos
  PutU16(&p, 0x0567);  // ypos
  PutU16(&p, 0xFFFB);  // th = -5
  PutU16(&p, 300);     // lvel
  PutU16(&p, 0xFF38);  // rvel = -200
  p.push_back(124);    // battery 12.4 V
  p.push_back(0x01);
  p.push_back(0x02);
  PutU16(&p, 0x8000);  // control
  PutU16(&p, 0x0102);  // flags
  p.push_back(45);     // compass
  p.push_back(static_cast<uint8_t>(sonars.size()));
  for (auto [index, range] : sonars) {
    p.push_back(index);
    PutU16(&p, range);
  }
  PutU16(&p, 4321);  // timer
  p.push_back(7);    // analog
  p.push_back(8);    // digin
  p.push_back(9);    // digout
  return p;
}

TEST(P2osCommands, HostCommandsAndTheirDecoding) {
  EXPECT_EQ(EncodeOpen(), (Bytes{0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01}));
  EXPECT_EQ(EncodePulse(), (Bytes{0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00}));
  EXPECT_EQ(EncodeSonarOn(), (Bytes{0xFA, 0xFB, 0x06, 0x1C, 0x3B, 0x01, 0x00, 0x1D, 0x3B}));
  const Bytes neg = EncodeCommandInt(21, -300);
  EXPECT_EQ(Bytes(neg.begin() + 3, neg.end() - 2), (Bytes{21, 0x1B, 0x2C, 0x01}));
  const auto c = DecodeHostCommand(Parsed(neg));
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->command, 21);
  EXPECT_EQ(c->argument, -300);
  const auto sonar = DecodeHostCommand(Parsed(EncodeSonarOn()));
  ASSERT_TRUE(sonar.has_value());
  EXPECT_EQ(sonar->command, kCmdSonar);
  EXPECT_EQ(sonar->argument, 1);
  const auto pulse = DecodeHostCommand(Parsed(EncodePulse()));
  ASSERT_TRUE(pulse.has_value());
  EXPECT_EQ(pulse->command, kCmdPulse);
  EXPECT_FALSE(pulse->argument.has_value());
  const Bytes huge = EncodeCommandInt(21, 100000);  // clamped to u16
  EXPECT_EQ(DecodeHostCommand(Parsed(huge))->argument, 65535);
}

TEST(P2osSync, EchoesAndIdentity) {
  for (int n = 0; n < 3; ++n) EXPECT_EQ(SyncEcho(Parsed(EncodeSyncReply(n))), n);
  const RobotIdentity id{"Pioneer", "Pioneer", "p3dx-sh"};
  const Bytes reply = EncodeSync2Reply(id);
  Bytes expected_payload{0x02};
  for (const char* s : {"Pioneer", "Pioneer", "p3dx-sh"}) {
    expected_payload.insert(expected_payload.end(), s, s + std::strlen(s));
    expected_payload.push_back(0);
  }
  const PacketView v = Parsed(reply);
  EXPECT_EQ(Bytes(v.payload.begin(), v.payload.end()), expected_payload);
  EXPECT_EQ(SyncEcho(v), 2);
  EXPECT_EQ(DecodeSync2Reply(v), id);
  EXPECT_FALSE(DecodeSync2Reply(Parsed(EncodeSync(1))).has_value());
  EXPECT_FALSE(SyncEcho(Parsed(EncodeSonarOn())).has_value());
  // A last field without its NUL is tolerated.
  const Bytes no_nul{0x02, 'a', 0, 'b', 0, 'c'};
  EXPECT_EQ(DecodeSync2Reply(Parsed(EncodePacket(no_nul))), (RobotIdentity{"a", "b", "c"}));
}

TEST(P2osSip, DecodesTheSpecFieldLayout) {
  const Bytes payload = HandSip({{3, 1500}, {15, 5000}, {20, 700}});
  StandardSip sip;
  ASSERT_EQ(DecodeStandardSip(Parsed(EncodePacket(payload)), &sip), SipDecode::kOk);
  EXPECT_EQ(sip.type, 0x33);
  EXPECT_EQ(sip.xpos, 0x1234);
  EXPECT_EQ(sip.ypos, 0x0567);
  EXPECT_EQ(sip.th, -5);
  EXPECT_EQ(sip.lvel, 300);
  EXPECT_EQ(sip.rvel, -200);
  EXPECT_EQ(sip.battery_dv, 124);
  EXPECT_EQ(sip.stall_left, 1);
  EXPECT_EQ(sip.stall_right, 2);
  EXPECT_EQ(sip.control, -32768);
  EXPECT_EQ(sip.flags, 0x0102);
  EXPECT_EQ(sip.compass, 45);
  ASSERT_EQ(sip.sonars.size(), 3u);
  EXPECT_EQ(sip.sonars[0], (SonarRaw{3, 1500}));
  EXPECT_EQ(sip.sonars[1], (SonarRaw{15, 5000}));
  EXPECT_EQ(sip.timer, 4321);
  EXPECT_EQ(sip.analog, 7);
  EXPECT_EQ(sip.digin, 8);
  EXPECT_EQ(sip.digout, 9);
  // The encoder gives back the very same bytes.
  EXPECT_EQ(*EncodeStandardSip(sip), EncodePacket(payload));
}

TEST(P2osSip, TruncatedForeignAndExtended) {
  Bytes payload = HandSip({{1, 100}, {2, 200}});
  StandardSip sip;
  sip.sonars = {{9, 9}};
  for (std::size_t cut = 1; cut < payload.size(); ++cut) {
    EXPECT_EQ(DecodeStandardSip(Parsed(EncodePacket(Bytes(payload.begin(), payload.begin() + cut))),
                                &sip),
              SipDecode::kTruncated)
        << cut;
  }
  EXPECT_EQ(sip.sonars, (std::vector<SonarRaw>{{9, 9}}));  // untouched on failure
  Bytes foreign = payload;
  foreign[0] = 0x20;
  EXPECT_EQ(DecodeStandardSip(Parsed(EncodePacket(foreign)), &sip), SipDecode::kNotStandardSip);
  payload.insert(payload.end(), {1, 2, 3, 4});  // newer firmware's extra fields
  EXPECT_EQ(DecodeStandardSip(Parsed(EncodePacket(payload)), &sip), SipDecode::kOk);
  EXPECT_EQ(sip.digout, 9);
}

TEST(P2osSip, EncoderLimit) {
  StandardSip sip;
  sip.sonars.assign(76, SonarRaw{1, 2});
  const auto ok = EncodeStandardSip(sip);
  ASSERT_TRUE(ok.has_value());
  EXPECT_EQ(ok->size(), 3u + 20 + 3 * 76 + 5 + 2);
  sip.sonars.push_back(SonarRaw{1, 2});
  EXPECT_FALSE(EncodeStandardSip(sip).has_value());
}

TEST(SonarRing, P3dxPublishedGeometry) {
  const std::vector<SonarTransducer> ring = P3dxSonarRing();
  ASSERT_EQ(ring.size(), 16u);
  constexpr double kDeg = std::numbers::pi / 180.0;
  EXPECT_DOUBLE_EQ(ring[0].pose.x, 0.069);
  EXPECT_DOUBLE_EQ(ring[0].pose.y, 0.136);
  EXPECT_NEAR(ring[0].pose.theta, 90 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(ring[4].pose.x, 0.166);
  EXPECT_DOUBLE_EQ(ring[4].pose.y, -0.027);
  EXPECT_NEAR(ring[4].pose.theta, -10 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(ring[11].pose.x, -0.255);
  EXPECT_NEAR(ring[11].pose.theta, -170 * kDeg, 1e-12);
  EXPECT_NEAR(ring[12].pose.theta, 170 * kDeg, 1e-12);
  // Left-right mirror symmetry: transducer i and 7 - i (front), 8 + j and 15 - j (rear).
  for (int i = 0; i < 8; ++i) {
    const int m = 7 - i;
    EXPECT_DOUBLE_EQ(ring[i].pose.x, ring[m].pose.x);
    EXPECT_DOUBLE_EQ(ring[i].pose.y, -ring[m].pose.y);
    EXPECT_DOUBLE_EQ(ring[8 + i].pose.y, -ring[15 - i].pose.y);
  }
}

TEST(SonarRing, B21EvenlySpaced) {
  const std::vector<SonarTransducer> ring = B21SonarRing();
  ASSERT_EQ(ring.size(), 24u);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    EXPECT_NEAR(std::hypot(ring[i].pose.x, ring[i].pose.y), 0.26, 1e-12);
    EXPECT_NEAR(std::atan2(ring[i].pose.y, ring[i].pose.x), ring[i].pose.theta, 1e-9);
    const double next = ring[(i + 1) % 24].pose.theta;
    EXPECT_NEAR(WrapAngle(next - ring[i].pose.theta), 15 * std::numbers::pi / 180, 1e-12);
  }
  EXPECT_NEAR(ring[6].pose.x, 0.0, 1e-12);
  EXPECT_NEAR(ring[6].pose.y, 0.26, 1e-12);
}

TEST(SonarOptions, Validate) {
  EXPECT_EQ(SonarOptions{}.Validate(), "");
  SonarOptions o;
  o.range_factor_mm = 0.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.ring.clear();
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.ring[3].max_range = -1;
  EXPECT_NE(o.Validate(), "");
}

TEST(SonarReading, ConvertsWithFactorAndGeometry) {
  StandardSip sip;
  sip.sonars = {{3, 1500}, {15, 5000}, {20, 700}, {0, 0}};
  SonarOptions options;  // P3-DX, 1 mm per unit, max range 5 m
  SonarReading reading;
  const SonarConversion c = ToSonarReading(sip, FromSeconds(3.0), options, &reading);
  EXPECT_EQ(c.returns, 3);
  EXPECT_EQ(c.no_return, 1);
  EXPECT_EQ(c.unknown_transducer, 1);
  EXPECT_EQ(reading.stamp, FromSeconds(3.0));
  ASSERT_EQ(reading.returns.size(), 3u);
  EXPECT_EQ(reading.returns[0].transducer, 3);
  EXPECT_FLOAT_EQ(reading.returns[0].range, 1.5f);
  EXPECT_EQ(reading.returns[1].transducer, 15);
  EXPECT_FALSE(IsReturn(reading.returns[1].range));
  EXPECT_FLOAT_EQ(reading.returns[2].range, 0.0f);

  options.range_factor_mm = 0.268;  // an older controller's units
  options.ring = B21SonarRing();
  ToSonarReading(sip, Time{}, options, &reading);
  ASSERT_EQ(reading.returns.size(), 4u);  // index 20 exists on the 24-ring
  EXPECT_FLOAT_EQ(reading.returns[0].range, static_cast<float>(1500 * 0.268e-3));
  EXPECT_FLOAT_EQ(reading.returns[1].range, static_cast<float>(5000 * 0.268e-3));
}

TEST(SonarReading, FakeControllerInverse) {
  SonarOptions options;
  options.range_factor_mm = 0.268;
  SonarReading reading;
  reading.returns = {{0, 1.0f}, {5, kNoReturn}, {7, 4.999f}, {99, 1.0f}};
  StandardSip sip;
  sip.sonars = ToSonarRaw(reading, options);
  ASSERT_EQ(sip.sonars.size(), 3u);
  EXPECT_EQ(sip.sonars[0].range, 3731);  // 1000 / 0.268 = 3731.3
  SonarReading back;
  ToSonarReading(sip, Time{}, options, &back);
  ASSERT_EQ(back.returns.size(), 3u);
  EXPECT_NEAR(back.returns[0].range, 1.0, 0.268e-3 / 2);
  EXPECT_FALSE(IsReturn(back.returns[1].range));
  EXPECT_NEAR(back.returns[2].range, 4.999, 0.268e-3 / 2);
}

}  // namespace
}  // namespace atlas::p2os
