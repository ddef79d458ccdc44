#pragma once
// Runs the atlas-fakedev executable as a separate process for the round-trip tests, and
// reconstructs what it sent (its schedule is deterministic when it waits for the drivers).

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_p2os.h"
#include "drivers/fake/playback.h"

namespace atlas::hil {

class FakedevProcess {
 public:
  ~FakedevProcess() { Kill(); }

  bool Launch(const std::string& dir, const std::vector<std::string>& args, std::string* error) {
    dir_ = dir;
    out_ = dir + ".out";
    pid_ = fork();
    if (pid_ < 0) {
      *error = "fork failed";
      return false;
    }
    if (pid_ == 0) {
      const int fd = open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, 1);
      dup2(fd, 2);
      std::vector<char*> argv;
      std::string exe = ATLAS_FAKEDEV;
      argv.push_back(exe.data());
      std::vector<std::string> copy = args;
      for (auto& a : copy) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(exe.c_str(), argv.data());
      _exit(127);
    }
    return true;
  }

  // Waits until the devices exist (links and socket) or the process died.
  bool WaitForDevices(int timeout_ms) {
    for (int t = 0; t < timeout_ms; t += 10) {
      struct stat st;
      if (lstat((dir_ + "/laser").c_str(), &st) == 0 &&
          lstat((dir_ + "/sonar").c_str(), &st) == 0 && lstat((dir_ + "/can").c_str(), &st) == 0)
        return true;
      if (Exited()) return false;
      usleep(10000);
    }
    return false;
  }

  bool Exited() {
    if (pid_ <= 0) return true;
    if (waitpid(pid_, &status_, WNOHANG) == pid_) {
      pid_ = -1;
      return true;
    }
    return false;
  }
  int exit_code() const { return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1; }

  void Kill() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, &status_, 0);
      pid_ = -1;
    }
  }

  std::string Output() const {
    std::ifstream f(out_);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }

  // Counts from the closing "done" line.
  struct Counts {
    unsigned long scans = 0, odometry = 0, sips = 0;
    bool ok = false;
  };
  Counts DoneCounts() const {
    Counts c;
    const std::string out = Output();
    const size_t at = out.rfind("done ");
    if (at == std::string::npos) return c;
    const std::string line = out.substr(at, out.find('\n', at) - at);
    const size_t l = line.find("laser "), o = line.find("odometry "), s = line.find("sonar ");
    if (l == std::string::npos || o == std::string::npos || s == std::string::npos) return c;
    c.scans = std::stoul(line.substr(l + 6));
    c.odometry = std::stoul(line.substr(o + 9));
    c.sips = std::stoul(line.substr(s + 6));
    c.ok = true;
    return c;
  }

 private:
  pid_t pid_ = -1;
  int status_ = 0;
  std::string dir_, out_;
};

// The 0x311 ticks atlas-fakedev sends when every tick reaches the driver.
inline std::vector<fake::SentOdometry> ExpectedOdometry(const fake::Recording& rec, size_t n) {
  std::vector<fake::SentOdometry> out;
  for (size_t k = 0; k < n; ++k) {
    fake::SentOdometry s;
    s.tick = k;
    s.log_time = rec.begin + std::chrono::milliseconds(20) * static_cast<int64_t>(k);
    s.pose = rec.OdometryAt(s.log_time);
    out.push_back(s);
  }
  return out;
}

// The SIPs' sonar readings atlas-fakedev sends (P3-DX ring) when the controller was opened
// before the clock started: one every 100 ms of log time from the first stamp.
inline std::vector<SonarReading> ExpectedSonar(const fake::Recording& rec) {
  std::vector<SonarReading> out;
  const auto ring = p2os::P3dxSonarRing();
  for (Time t = rec.begin; t <= rec.end; t += std::chrono::milliseconds(100)) {
    size_t i = 0;
    while (i + 1 < rec.scans.size() && rec.scans[i + 1].stamp <= t) ++i;
    if (rec.scans[i].stamp > t) continue;
    out.push_back(fake::SonarFromScan(rec.scans[i], ring));
  }
  return out;
}

}  // namespace atlas::hil
