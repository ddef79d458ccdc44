#include "drivers/fake/fake_serial_device.h"

#include <algorithm>

namespace atlas::fake {

FakeSerialDevice::FakeSerialDevice(std::string name, std::string link, FaultOptions faults,
                                   std::shared_ptr<const PlaybackClock> clock)
    : name_(std::move(name)), link_(std::move(link)), faults_(faults), clock_(std::move(clock)) {}

FakeSerialDevice::~FakeSerialDevice() { Stop(); }

bool FakeSerialDevice::Open(std::string* error) {
  if (!pty_.Create(link_, error)) {
    *error = name_ + ": " + *error;
    return false;
  }
  std::lock_guard<std::mutex> lock(path_mutex_);
  path_ = pty_.path();
  return true;
}

std::string FakeSerialDevice::path() const {
  std::lock_guard<std::mutex> lock(path_mutex_);
  return path_;
}

void FakeSerialDevice::Start() {
  if (thread_.joinable()) return;
  OnPowerUp();
  stop_.store(false);
  thread_ = std::thread([this] { Loop(); });
}

void FakeSerialDevice::Stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  pty_.Close();
}

bool FakeSerialDevice::Stalled(Time now) const {
  if (faults_.stall_after_s < 0 || !clock_->started()) return false;
  const double t = ToSeconds(now - clock_->WallAt(clock_->log_start()));
  return t >= faults_.stall_after_s && t < faults_.stall_after_s + faults_.stall_for_s;
}

bool FakeSerialDevice::SendReply(const std::vector<uint8_t>& bytes) {
  if (Stalled(Now())) return false;
  return pty_.WriteAll(bytes.data(), bytes.size(), 1000);
}

bool FakeSerialDevice::SendMessage(std::vector<uint8_t> bytes) {
  if (Stalled(Now()) || bytes.empty()) return false;
  ++message_index_;
  auto every = [&](int n) { return n > 0 && message_index_ % static_cast<uint64_t>(n) == 0; };
  if (every(faults_.garbage_every)) {
    const std::string g =
        GarbageBytes(faults_.garbage_bytes, static_cast<uint32_t>(message_index_));
    if (pty_.WriteAll(reinterpret_cast<const uint8_t*>(g.data()), g.size(), 1000))
      counts_.garbage.fetch_add(1, std::memory_order_relaxed);
  }
  bool intact = true;
  if (every(faults_.corrupt_crc_every)) {
    bytes.back() ^= 0x5A;
    counts_.corrupted.fetch_add(1, std::memory_order_relaxed);
    intact = false;
  } else if (every(faults_.truncate_every)) {
    bytes.resize(bytes.size() / 2);
    counts_.truncated.fetch_add(1, std::memory_order_relaxed);
    intact = false;
  }
  if (!pty_.WriteAll(bytes.data(), bytes.size(), 1000)) return false;
  messages_sent_.fetch_add(1, std::memory_order_relaxed);
  return intact;
}

bool FakeSerialDevice::SleepInterruptible(Duration d) {
  const Time until = Now() + d;
  while (!stop_.load()) {
    const Time now = Now();
    if (now >= until) return true;
    std::this_thread::sleep_for(std::min<Duration>(until - now, std::chrono::milliseconds(10)));
  }
  return false;
}

void FakeSerialDevice::Loop() {
  uint8_t buf[2048];
  while (!stop_.load()) {
    const Time now = Now();
    if (clock_->started() && faults_.drop_after_s >= 0 && !dropped_ &&
        ToSeconds(now - clock_->WallAt(clock_->log_start())) >= faults_.drop_after_s) {
      dropped_ = true;
      pty_.Close();
      counts_.drops.fetch_add(1, std::memory_order_relaxed);
      if (!SleepInterruptible(std::chrono::duration_cast<Duration>(
              std::chrono::duration<double>(faults_.drop_for_s))))
        break;
      std::string error;
      while (!pty_.Create(link_, &error)) {
        if (!SleepInterruptible(std::chrono::milliseconds(100))) return;
      }
      {
        std::lock_guard<std::mutex> lock(path_mutex_);
        path_ = pty_.path();
      }
      OnPowerUp();
      continue;
    }
    if (Stalled(now) && !stall_counted_) {
      stall_counted_ = true;
      counts_.stalls.fetch_add(1, std::memory_order_relaxed);
    }
    Time next = now + std::chrono::milliseconds(20);
    if (clock_->started()) next = std::min(next, Tick(now));
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - Now());
    const long n =
        pty_.Read(buf, sizeof(buf), static_cast<int>(std::clamp<int64_t>(wait.count(), 0, 20)));
    if (n > 0) OnHostBytes(std::span<const uint8_t>(buf, static_cast<size_t>(n)), Now());
  }
}

}  // namespace atlas::fake
