#pragma once
// Test rig for the drivers against the fake devices, in one process but over the real
// transports: a pseudo-terminal per serial device (fake LMS, fake P2OS) and the fake CAN bus's
// Unix socket (fake AgileX base). The fakes play a recording on a shared playback clock;
// the readers (LaserReader, OdometryReader, SonarReader) run their own threads; the rig drains
// their queues like the daemon's step loop (never blocking) and keeps what came out.

#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "atlas_paths.h"
#include "drivers/device/laser_reader.h"
#include "drivers/device/odometry_reader.h"
#include "drivers/device/sonar_reader.h"
#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_lms.h"
#include "drivers/fake/fake_p2os.h"
#include "drivers/fake/playback.h"

namespace atlas::hil {

inline std::string MitCsailPath() {
  return std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.clf.gz";
}

// The log, read once per process; `max_scans` 0 = all.
inline std::shared_ptr<const fake::Recording> LoadMitCsail(size_t max_scans, std::string* error) {
  auto rec = std::make_shared<fake::Recording>();
  if (!fake::LoadCarmenRecording(MitCsailPath(), max_scans, rec.get(), error)) return nullptr;
  return rec;
}

struct RigOptions {
  double speed = 10.0;
  // Non-empty: the devices are provided by another process (atlas-fakedev --dir external_dir);
  // the rig runs the drivers only, against external_dir/laser, /can and /sonar.
  std::string external_dir;
  bool laser = true, odometry = true, sonar = true;
  fake::FaultOptions laser_faults, odometry_faults, sonar_faults;
  int lms_power_up_baud = 9600;
};

class DriverRig {
 public:
  DriverRig(std::shared_ptr<const fake::Recording> rec, const RigOptions& o) : rec_(rec), o_(o) {
    char tmpl[] = "/tmp/atlas_hil_XXXXXX";
    dir_ = o.external_dir.empty() ? std::string(mkdtemp(tmpl)) : o.external_dir;
    clock_ = std::make_shared<fake::PlaybackClock>(rec->begin, o.speed);
    ReconnectOptions rc;
    rc.initial_backoff = std::chrono::milliseconds(20);
    rc.max_backoff = std::chrono::milliseconds(200);
    rc.stall_timeout = std::chrono::milliseconds(400);
    rc.reopen_after_silence = std::chrono::milliseconds(1500);
    const bool own = o.external_dir.empty();
    if (o.laser) {
      fake::FakeLmsOptions fo;
      fo.link = dir_ + "/laser";
      fo.power_up_baud = o.lms_power_up_baud;
      fo.faults = o.laser_faults;
      if (own) lms_ = std::make_unique<fake::FakeLms>(fo, rec, clock_);
      LaserReaderOptions lo;
      lo.device = fo.link;
      lo.baud = 500000;
      lo.reconnect = rc;
      lo.queue_capacity = 256;
      laser_opts_ = lo;
    }
    if (o.odometry) {
      fake::FakeAgilexOptions fo;
      fo.socket_path = dir_ + "/can";
      fo.faults = o.odometry_faults;
      if (own) base_ = std::make_unique<fake::FakeAgilexBase>(fo, rec, clock_);
      OdometryReaderOptions oo;
      oo.interface_name = "unix:" + fo.socket_path;
      // At `speed` times real time the wheels seem to turn `speed` times faster, and the
      // fake's scheduling jitter (frames sent in bursts) is worth `speed` times more travel.
      oo.odometry.max_speed_mps = 3.0 * o.speed;
      oo.odometry.slack_m = 0.02 * o.speed;
      oo.reconnect = rc;
      oo.queue_capacity = 4096;
      odo_opts_ = oo;
    }
    if (o.sonar) {
      fake::FakeP2osOptions fo;
      fo.link = dir_ + "/sonar";
      fo.faults = o.sonar_faults;
      if (own) p2os_ = std::make_unique<fake::FakeP2os>(fo, rec, clock_);
      SonarReaderOptions so;
      so.device = fo.link;
      so.reconnect = rc;
      so.queue_capacity = 256;
      sonar_opts_ = so;
    }
  }
  ~DriverRig() {
    if (laser_) laser_->Stop();
    if (odo_) odo_->Stop();
    if (sonar_) sonar_->Stop();
    if (lms_) lms_->Stop();
    if (base_) base_->Stop();
    if (p2os_) p2os_->Stop();
    std::error_code ec;
    if (o_.external_dir.empty()) std::filesystem::remove_all(dir_, ec);
  }

  // Opens the fakes, starts the drivers, waits until every driver is running, starts the
  // clock. False (with *error) if that takes longer than `timeout`.
  bool Start(std::string* error, Duration timeout = std::chrono::seconds(10)) {
    if (!o_.external_dir.empty()) return StartExternal(error, timeout);
    if (lms_ && (!lms_->Open(error))) return false;
    if (base_ && !base_->Open(error)) return false;
    if (p2os_ && !p2os_->Open(error)) return false;
    if (lms_) lms_->Start();
    if (base_) base_->Start();
    if (p2os_) p2os_->Start();
    if (lms_) {
      if (std::string e = laser_opts_.Validate(); !e.empty()) return Fail(e, error);
      laser_ = std::make_unique<LaserReader>(laser_opts_);
      laser_->Start();
    }
    if (base_) {
      if (std::string e = odo_opts_.Validate(); !e.empty()) return Fail(e, error);
      odo_ = std::make_unique<OdometryReader>(odo_opts_);
      odo_->Start();
    }
    if (p2os_) {
      if (std::string e = sonar_opts_.Validate(); !e.empty()) return Fail(e, error);
      sonar_ = std::make_unique<SonarReader>(sonar_opts_);
      sonar_->Start();
    }
    const Time deadline = Now() + timeout;
    while (Now() < deadline) {
      const bool l =
          !lms_ || (laser_->Health().state == DriverState::kRunning && lms_->streaming());
      const bool b =
          !base_ || (odo_->Health().state == DriverState::kRunning && base_->clients() > 0);
      const bool s =
          !p2os_ || (sonar_->Health().state == DriverState::kRunning && p2os_->is_open());
      if (l && b && s) {
        clock_->Start();
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return Fail("drivers did not start in time", error);
  }

  // Drivers only, the devices being another process's; returns once every driver runs.
  bool StartExternal(std::string* error, Duration timeout) {
    laser_ = std::make_unique<LaserReader>(laser_opts_);
    odo_ = std::make_unique<OdometryReader>(odo_opts_);
    sonar_ = std::make_unique<SonarReader>(sonar_opts_);
    laser_->Start();
    odo_->Start();
    sonar_->Start();
    const Time deadline = Now() + timeout;
    while (Now() < deadline) {
      if (laser_->Health().state == DriverState::kRunning &&
          odo_->Health().state == DriverState::kRunning &&
          sonar_->Health().state == DriverState::kRunning)
        return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return Fail("drivers did not start in time: " + laser_->Health().last_error + " / " +
                    odo_->Health().last_error + " / " + sonar_->Health().last_error,
                error);
  }

  // Drains the queues; true when something came out.
  bool Drain() {
    bool any = false;
    LaserScan scan;
    while (laser_ && laser_->Pop(&scan)) {
      scans.push_back(std::move(scan));
      any = true;
    }
    OdometrySample o;
    while (odo_ && odo_->Pop(&o)) {
      odometry.push_back(o);
      any = true;
    }
    SonarReading r;
    while (sonar_ && sonar_->Pop(&r)) {
      sonar.push_back(std::move(r));
      any = true;
    }
    return any;
  }

  bool Finished() const {
    return (!lms_ || lms_->finished()) && (!base_ || base_->finished()) &&
           (!p2os_ || p2os_->finished());
  }

  // Runs until every fake has played the recording and the queues stayed empty for 300 ms.
  void RunToEnd(Duration limit) {
    const Time deadline = Now() + limit;
    Time quiet_since = Now();
    while (Now() < deadline) {
      if (Drain()) quiet_since = Now();
      if (Finished() && states_at_end.empty()) {
        for (DeviceReader* r :
             std::initializer_list<DeviceReader*>{laser_.get(), odo_.get(), sonar_.get()})
          if (r) states_at_end.push_back(r->Health().state);
      }
      if (Finished() && Now() - quiet_since > std::chrono::milliseconds(300)) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    Drain();
  }

  std::shared_ptr<const fake::Recording> rec_;
  RigOptions o_;
  std::string dir_;
  std::shared_ptr<fake::PlaybackClock> clock_;
  std::unique_ptr<fake::FakeLms> lms_;
  std::unique_ptr<fake::FakeAgilexBase> base_;
  std::unique_ptr<fake::FakeP2os> p2os_;
  LaserReaderOptions laser_opts_;
  OdometryReaderOptions odo_opts_;
  SonarReaderOptions sonar_opts_;
  std::unique_ptr<LaserReader> laser_;
  std::unique_ptr<OdometryReader> odo_;
  std::unique_ptr<SonarReader> sonar_;

  std::vector<LaserScan> scans;
  std::vector<OdometrySample> odometry;
  std::vector<SonarReading> sonar;
  std::vector<DriverState> states_at_end;  // when the last fake finished playing

 private:
  static bool Fail(const std::string& e, std::string* error) {
    *error = e;
    return false;
  }
};

// Compares received scans with the recording's, in order, given which indices were sent
// intact. Returns the number of mismatching scans; *first_error describes the first.
inline size_t CompareScans(const fake::Recording& rec, const std::vector<size_t>& sent,
                           const std::vector<LaserScan>& got, std::string* first_error) {
  size_t bad = 0;
  auto fail = [&](const std::string& e) {
    if (bad++ == 0) *first_error = e;
  };
  if (sent.size() != got.size())
    fail("sent " + std::to_string(sent.size()) + " scans, got " + std::to_string(got.size()));
  for (size_t k = 0; k < std::min(sent.size(), got.size()); ++k) {
    const LaserScan& a = rec.scans[sent[k]];
    const LaserScan& b = got[k];
    if (a.ranges.size() != b.ranges.size()) {
      fail("scan " + std::to_string(k) + ": beam count");
      continue;
    }
    for (size_t i = 0; i < a.ranges.size(); ++i) {
      const bool ra = IsReturn(a.ranges[i]), rb = IsReturn(b.ranges[i]);
      if (ra != rb || (ra && std::abs(a.ranges[i] - b.ranges[i]) > 0.0051f)) {
        char m[160];
        std::snprintf(m, sizeof(m), "scan %zu (log %zu) beam %zu: log %.4f, driver %.4f", k,
                      sent[k], i, a.ranges[i], b.ranges[i]);
        fail(m);
        break;
      }
    }
  }
  return bad;
}

// Matches each message out, in order, with the next message sent intact that `same(k, out)`
// says it equals (k indexes the messages sent intact). unmatched: messages out that match
// none; missing_runs: the unbroken runs of consecutive sent messages that did not come out (a
// reconnection loses one or two runs, however long it takes).
struct InOrderMatch {
  size_t unmatched = 0;
  size_t matched = 0;
  size_t missing_runs = 0;
};

template <typename Out, typename Same>
InOrderMatch MatchInOrder(size_t sent_count, const std::vector<Out>& got, Same same) {
  InOrderMatch m;
  size_t j = 0;
  for (const Out& g : got) {
    size_t k = j;
    while (k < sent_count && !same(k, g)) ++k;
    if (k == sent_count) {
      ++m.unmatched;
      continue;
    }
    m.missing_runs += k > j;
    j = k + 1;
    ++m.matched;
  }
  m.missing_runs += j < sent_count;
  return m;
}

// For runs with faults: every scan out must equal a scan sent intact, in order; scans sent
// intact may be missing (written just before an unplug, or while the driver was reopening
// the line). Returns the number of scans out that match none; *missing counts the scans sent
// intact that did not come out, *missing_runs the unbroken runs they form (MatchInOrder).
inline size_t CompareScansInOrder(const fake::Recording& rec, const std::vector<size_t>& sent,
                                  const std::vector<LaserScan>& got, size_t* missing,
                                  size_t* missing_runs) {
  auto same = [&](size_t k, const LaserScan& b) {
    const LaserScan& a = rec.scans[sent[k]];
    if (a.ranges.size() != b.ranges.size()) return false;
    for (size_t i = 0; i < a.ranges.size(); ++i) {
      const bool ra = IsReturn(a.ranges[i]), rb = IsReturn(b.ranges[i]);
      if (ra != rb || (ra && std::abs(a.ranges[i] - b.ranges[i]) > 0.0051f)) return false;
    }
    return true;
  };
  const InOrderMatch m = MatchInOrder(sent.size(), got, same);
  *missing = sent.size() - m.matched;
  *missing_runs = m.missing_runs;
  return m.unmatched;
}

}  // namespace atlas::hil
