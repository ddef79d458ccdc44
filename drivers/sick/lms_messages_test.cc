#include "drivers/sick/lms_messages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <numbers>
#include <vector>

namespace atlas::sick {
namespace {

using Bytes = std::vector<uint8_t>;

// Parses a whole telegram whose bytes are kept alive for the rest of the test program, so that
// the view may outlive the caller's temporary.
TelegramView Parsed(const Bytes& whole) {
  static std::deque<Bytes> kept;
  kept.push_back(whole);
  TelegramView v;
  EXPECT_EQ(ParseTelegram(kept.back(), &v), TelegramParse::kOk);
  return v;
}

// A B0 reply built by hand (not by the encoder under test).
Bytes B0(uint16_t count_word, const std::vector<uint16_t>& words, uint8_t status) {
  Bytes d{static_cast<uint8_t>(count_word & 0xFF), static_cast<uint8_t>(count_word >> 8)};
  for (uint16_t w : words) {
    d.push_back(static_cast<uint8_t>(w & 0xFF));
    d.push_back(static_cast<uint8_t>(w >> 8));
  }
  return EncodeTelegram(kScannerAddress, kReplyValues, d, status);
}

TEST(LmsHostCommands, EncodersGiveSpecBytes) {
  EXPECT_EQ(EncodeStatusRequest(), (Bytes{0x02, 0x00, 0x01, 0x00, 0x31, 0x15, 0x12}));
  EXPECT_EQ(EncodeModeBaud(Baud::k500000), (Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x48, 0x58, 0x08}));
  EXPECT_EQ(EncodeModeBaud(Baud::k9600), (Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x42, 0x52, 0x08}));
  EXPECT_EQ(EncodeScanRequest(), (Bytes{0x02, 0x00, 0x02, 0x00, 0x30, 0x01, 0x31, 0x18}));
  EXPECT_EQ(EncodeModeContinuous(), (Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x24, 0x34, 0x08}));
  EXPECT_EQ(EncodeModeOnRequest(), (Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x25, 0x35, 0x08}));
}

TEST(LmsHostCommands, InstallationModeAndVariantLayout) {
  const TelegramView inst = Parsed(EncodeModeInstallation());
  EXPECT_EQ(inst.command, kCmdMode);
  ASSERT_EQ(inst.data.size(), 9u);
  EXPECT_EQ(inst.data[0], 0x00);
  EXPECT_EQ(std::string(inst.data.begin() + 1, inst.data.end()), "SICK_LMS");
  const TelegramView var = Parsed(EncodeVariantRequest(180, 50));
  EXPECT_EQ(var.command, kCmdVariant);
  EXPECT_EQ(Bytes(var.data.begin(), var.data.end()), (Bytes{0xB4, 0x00, 0x32, 0x00}));
}

TEST(LmsHostCommands, FakeScannerDecodesEveryCommand) {
  using K = HostCommand::Kind;
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeStatusRequest())).kind, K::kStatus);
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeModeContinuous())).kind, K::kModeContinuous);
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeModeOnRequest())).kind, K::kModeOnRequest);
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeModeInstallation())).kind, K::kModeInstallation);
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeScanRequest())).kind, K::kScanRequest);
  for (Baud b : {Baud::k9600, Baud::k19200, Baud::k38400, Baud::k500000}) {
    const HostCommand c = DecodeHostCommand(Parsed(EncodeModeBaud(b)));
    EXPECT_EQ(c.kind, K::kModeBaud);
    EXPECT_EQ(c.baud, b);
  }
  const HostCommand v = DecodeHostCommand(Parsed(EncodeVariantRequest(100, 25)));
  EXPECT_EQ(v.kind, K::kVariant);
  EXPECT_EQ(v.angle_deg, 100);
  EXPECT_EQ(v.resolution_centideg, 25);
  const Bytes wrong_password{0x00, 'S', 'I', 'C', 'K', '_', 'L', 'M', 'X'};
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeTelegram(0, kCmdMode, wrong_password))).kind,
            K::kUnknown);
  const Bytes bad_baud{0x43};
  EXPECT_EQ(DecodeHostCommand(Parsed(EncodeTelegram(0, kCmdMode, bad_baud))).kind, K::kUnknown);
  const Bytes reply = EncodeModeReply(true, 0);
  EXPECT_EQ(DecodeHostCommand(Parsed(Bytes(reply.begin() + 1, reply.end()))).kind, K::kUnknown);
}

TEST(LmsBaud, RatesAndCodes) {
  EXPECT_EQ(BaudRate(Baud::k38400), 38400);
  EXPECT_EQ(static_cast<uint8_t>(Baud::k19200), 0x41);
  EXPECT_EQ(BaudFromRate(500000), Baud::k500000);
  EXPECT_FALSE(BaudFromRate(115200).has_value());
}

TEST(LmsReplies, ModeReplyIsTheSpecVector) {
  const Bytes r = EncodeModeReply(true, 0x10);
  EXPECT_EQ(r, (Bytes{0x06, 0x02, 0x80, 0x03, 0x00, 0xA0, 0x00, 0x10, 0x16, 0x0A}));
  const auto m = DecodeModeReply(Parsed(Bytes(r.begin() + 1, r.end())));
  ASSERT_TRUE(m.has_value());
  EXPECT_TRUE(m->success);
  EXPECT_EQ(m->status.level(), StatusLevel::kOk);
  const Bytes fail = EncodeModeReply(false, 0x03);
  const auto f = DecodeModeReply(Parsed(Bytes(fail.begin() + 1, fail.end())));
  ASSERT_TRUE(f.has_value());
  EXPECT_FALSE(f->success);
  EXPECT_EQ(f->status.level(), StatusLevel::kError);
}

TEST(LmsReplies, StatusAndVariantRoundTrip) {
  const Bytes s = EncodeStatusReply(0x10, "V02.30 ");
  ASSERT_EQ(s[0], kAck);
  const TelegramView sv = Parsed(Bytes(s.begin() + 1, s.end()));
  EXPECT_EQ(sv.command, kReplyStatus);
  EXPECT_EQ(sv.data.size(), 152u);
  const auto st = DecodeStatusReply(sv);
  ASSERT_TRUE(st.has_value());
  EXPECT_EQ(st->software_version, "V02.30");
  EXPECT_FALSE(DecodeVariantReply(sv).has_value());

  const Bytes v = EncodeVariantReply(true, 180, 50, 0x10);
  const TelegramView vv = Parsed(Bytes(v.begin() + 1, v.end()));
  EXPECT_EQ(Bytes(vv.data.begin(), vv.data.end()), (Bytes{0x01, 0xB4, 0x00, 0x32, 0x00}));
  const auto var = DecodeVariantReply(vv);
  ASSERT_TRUE(var.has_value());
  EXPECT_TRUE(var->accepted);
  EXPECT_EQ(var->angle_deg, 180);
  EXPECT_EQ(var->resolution_centideg, 50);

  const Bytes nc = EncodeIncorrectCommandReply(0x00);
  EXPECT_EQ(Parsed(Bytes(nc.begin() + 1, nc.end())).command, kReplyIncorrectCommand);
}

TEST(LmsStatus, LevelsAndPollution) {
  EXPECT_EQ(ScannerStatus{0x00}.level(), StatusLevel::kOk);
  EXPECT_EQ(ScannerStatus{0x10}.level(), StatusLevel::kOk);
  EXPECT_EQ(ScannerStatus{0x03}.level(), StatusLevel::kError);
  EXPECT_EQ(ScannerStatus{0x04}.level(), StatusLevel::kFatal);
  EXPECT_EQ(ScannerStatus{0x07}.level(), StatusLevel::kOther);
  EXPECT_TRUE(ScannerStatus{0x80}.pollution());
  EXPECT_FALSE(ScannerStatus{0x04}.pollution());
}

TEST(LmsMeasuredValues, HandBuilt181MillimetreScan) {
  std::vector<uint16_t> words(181, 1000);
  words[0] = 0xE000 | 1234;  // field flags A/B/C set: masked off
  words[1] = 0;
  for (int i = 0; i < 9; ++i) words[10 + i] = static_cast<uint16_t>(8183 + i);  // no return
  words[180] = 8182;
  const uint16_t count_word = 181 | (1 << 14) | (2 << 11);  // mm, partial scan 2
  const TelegramView t = Parsed(B0(count_word, words, 0x83));
  LaserScan scan;
  ScanInfo info;
  ScanOptions options;
  options.sensor_pose = Pose2{0.1, 0.0, 0.0};
  ASSERT_EQ(DecodeMeasuredValues(t, FromSeconds(12.5), options, &scan, &info), ScanDecode::kOk);
  EXPECT_EQ(scan.stamp, FromSeconds(12.5));
  ASSERT_EQ(scan.ranges.size(), 181u);
  EXPECT_FLOAT_EQ(scan.angle_min, static_cast<float>(-std::numbers::pi / 2));
  EXPECT_FLOAT_EQ(scan.angle_increment, static_cast<float>(std::numbers::pi / 180));
  EXPECT_NEAR(scan.angle_min + 180 * scan.angle_increment, std::numbers::pi / 2, 1e-5);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.234f);
  EXPECT_FLOAT_EQ(scan.ranges[1], 0.0f);
  EXPECT_FLOAT_EQ(scan.ranges[2], 1.0f);
  for (int i = 10; i < 19; ++i) EXPECT_FALSE(IsReturn(scan.ranges[i])) << i;
  EXPECT_FLOAT_EQ(scan.ranges[180], 8.182f);
  EXPECT_FLOAT_EQ(scan.max_range, 8.182f);
  EXPECT_EQ(scan.sensor_pose.x, 0.1);
  EXPECT_EQ(info.count, 181);
  EXPECT_EQ(info.unit, Unit::kMillimetre);
  EXPECT_EQ(info.partial_scan, 2);
  EXPECT_EQ(info.no_return_beams, 9);
  EXPECT_EQ(info.status.level(), StatusLevel::kError);
  EXPECT_TRUE(info.status.pollution());
}

TEST(LmsMeasuredValues, CentimetreUnitAndHalfDegree) {
  const TelegramView t = Parsed(B0(361, std::vector<uint16_t>(361, 500), 0x00));
  LaserScan scan;
  ScanInfo info;
  ASSERT_EQ(DecodeMeasuredValues(t, Time{}, {}, &scan, &info), ScanDecode::kOk);
  EXPECT_EQ(info.unit, Unit::kCentimetre);
  EXPECT_FLOAT_EQ(scan.ranges[200], 5.0f);
  EXPECT_FLOAT_EQ(scan.angle_increment, static_cast<float>(std::numbers::pi / 360));
  EXPECT_FLOAT_EQ(scan.max_range, 81.82f);
}

TEST(LmsMeasuredValues, HundredDegreeVariants) {
  for (int n : {101, 201, 401}) {
    const TelegramView t = Parsed(B0(static_cast<uint16_t>(n), std::vector<uint16_t>(n, 1), 0));
    LaserScan scan;
    ASSERT_EQ(DecodeMeasuredValues(t, Time{}, {}, &scan, nullptr), ScanDecode::kOk) << n;
    EXPECT_FLOAT_EQ(scan.angle_min, static_cast<float>(-50 * std::numbers::pi / 180));
    EXPECT_NEAR(scan.angle_min + (n - 1) * scan.angle_increment, 50 * std::numbers::pi / 180, 1e-5);
  }
}

TEST(LmsMeasuredValues, RejectsMalformed) {
  LaserScan scan;
  scan.ranges = {7.0f};
  EXPECT_EQ(DecodeMeasuredValues(Parsed(B0(181, std::vector<uint16_t>(180, 1), 0)), Time{}, {},
                                 &scan, nullptr),
            ScanDecode::kLengthMismatch);
  EXPECT_EQ(DecodeMeasuredValues(Parsed(B0(181 | 0x8000, std::vector<uint16_t>(181, 1), 0)), Time{},
                                 {}, &scan, nullptr),
            ScanDecode::kBadUnit);
  EXPECT_EQ(DecodeMeasuredValues(Parsed(B0(180, std::vector<uint16_t>(180, 1), 0)), Time{}, {},
                                 &scan, nullptr),
            ScanDecode::kUnsupportedCount);
  EXPECT_EQ(DecodeMeasuredValues(Parsed(EncodeScanRequest()), Time{}, {}, &scan, nullptr),
            ScanDecode::kNotMeasuredValues);
  EXPECT_EQ(scan.ranges, std::vector<float>{7.0f});  // untouched on failure
}

TEST(LmsMeasuredValues, EncoderRoundsToTheUnitAndMapsNoReturns) {
  LaserScan scan;
  scan.ranges.assign(181, 2.0f);
  scan.ranges[0] = 1.2345f;
  scan.ranges[1] = kNoReturn;
  scan.ranges[2] = 100.0f;  // beyond 8182 mm
  scan.ranges[3] = -1.0f;
  scan.ranges[4] = std::nanf("");
  scan.ranges[5] = 8.1824f;
  const auto mm = EncodeMeasuredValues(scan, Unit::kMillimetre, 0x10);
  ASSERT_TRUE(mm.has_value());
  const TelegramView t = Parsed(*mm);
  EXPECT_EQ(t.data[0] | (t.data[1] << 8), 181 | (1 << 14));
  auto word = [&](int i) { return t.data[2 + 2 * i] | (t.data[3 + 2 * i] << 8); };
  EXPECT_EQ(word(0), 1235);  // 1234.5 mm, float slightly above: rounds up
  EXPECT_EQ(word(1), kCodeInvalid);
  EXPECT_EQ(word(2), kCodeAboveMaximum);
  EXPECT_EQ(word(3), kCodeInvalid);
  EXPECT_EQ(word(4), kCodeInvalid);
  EXPECT_EQ(word(5), 8182);
  EXPECT_EQ(word(6), 2000);
  LaserScan back;
  ScanInfo info;
  ASSERT_EQ(DecodeMeasuredValues(t, Time{}, {}, &back, &info), ScanDecode::kOk);
  EXPECT_EQ(info.no_return_beams, 4);
  EXPECT_EQ(info.status.raw, 0x10);

  const auto cm = EncodeMeasuredValues(scan, Unit::kCentimetre, 0x00);
  ASSERT_TRUE(cm.has_value());
  ASSERT_EQ(DecodeMeasuredValues(Parsed(*cm), Time{}, {}, &back, &info), ScanDecode::kOk);
  EXPECT_EQ(info.unit, Unit::kCentimetre);
  EXPECT_FLOAT_EQ(back.ranges[0], 1.23f);
  EXPECT_FALSE(IsReturn(back.ranges[2]));  // 10000 cm: above the maximum
}

TEST(LmsMeasuredValues, EncoderRoundTripsEveryRepresentableRange) {
  LaserScan scan;
  scan.ranges.resize(361);
  for (int v = 0; v < 8183; v += 361) {
    for (int i = 0; i < 361; ++i) scan.ranges[i] = static_cast<float>((v + i) % 8183 * 0.001);
    LaserScan back;
    ASSERT_EQ(DecodeMeasuredValues(Parsed(*EncodeMeasuredValues(scan, Unit::kMillimetre, 0)),
                                   Time{}, {}, &back, nullptr),
              ScanDecode::kOk);
    ASSERT_EQ(back.ranges, scan.ranges) << v;
  }
}

TEST(LmsMeasuredValues, EncoderRefusesWhatDoesNotFitATelegram) {
  LaserScan scan;
  EXPECT_FALSE(EncodeMeasuredValues(scan, Unit::kMillimetre, 0).has_value());
  scan.ranges.assign(405, 1.0f);
  EXPECT_FALSE(EncodeMeasuredValues(scan, Unit::kMillimetre, 0).has_value());
  scan.ranges.assign(404, 1.0f);
  const auto t = EncodeMeasuredValues(scan, Unit::kMillimetre, 0);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ((*t)[2] | ((*t)[3] << 8), 812);
}

}  // namespace
}  // namespace atlas::sick
