#include "tools/view/snapshot_hub.h"

namespace atlas::view {

bool SnapshotHub::TryOpenStream() {
  std::lock_guard<std::mutex> lock(mu_);
  if (stopped_ || streams_ >= max_streams_) return false;
  ++streams_;
  return true;
}

void SnapshotHub::CloseStream() {
  std::lock_guard<std::mutex> lock(mu_);
  if (streams_ > 0) --streams_;
}

int SnapshotHub::streams() const {
  std::lock_guard<std::mutex> lock(mu_);
  return streams_;
}

void SnapshotHub::Publish(std::string json) {
  auto update = std::make_shared<const std::string>(std::move(json));
  {
    std::lock_guard<std::mutex> lock(mu_);
    latest_ = std::move(update);
    ++seq_;
  }
  cv_.notify_all();
}

std::shared_ptr<const std::string> SnapshotHub::Latest(uint64_t* seq) const {
  std::lock_guard<std::mutex> lock(mu_);
  *seq = seq_;
  return latest_;
}

std::shared_ptr<const std::string> SnapshotHub::WaitNewer(uint64_t* seen, Duration timeout) {
  std::unique_lock<std::mutex> lock(mu_);
  cv_.wait_for(lock, timeout, [&] { return stopped_ || seq_ > *seen; });
  if (stopped_ || seq_ <= *seen) return nullptr;
  *seen = seq_;
  return latest_;
}

void SnapshotHub::Stop() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopped_ = true;
  }
  cv_.notify_all();
}

bool SnapshotHub::stopped() const {
  std::lock_guard<std::mutex> lock(mu_);
  return stopped_;
}

}  // namespace atlas::view
