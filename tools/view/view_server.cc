#include "tools/view/view_server.h"

#include <httplib.h>
#include <signal.h>

#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <thread>
#include <vector>

#include "core/common/time.h"
#include "tools/view/snapshot_hub.h"
#include "tools/view/view_json.h"
#include "tools/view/view_page.h"
#include "tools/view/view_state.h"

namespace atlas::view {
namespace {

// httplib's task queue with a fixed number of workers and a bounded queue: enqueue waits when
// the queue is full, which stops the accept loop (httplib's own ThreadPool queues without bound).
class BoundedTaskQueue : public httplib::TaskQueue {
 public:
  BoundedTaskQueue(size_t workers, size_t capacity) : capacity_(capacity) {
    for (size_t i = 0; i < workers; ++i) threads_.emplace_back([this] { Work(); });
  }
  void enqueue(std::function<void()> fn) override {
    std::unique_lock<std::mutex> lock(mu_);
    not_full_.wait(lock, [&] { return jobs_.size() < capacity_ || shutdown_; });
    jobs_.push_back(std::move(fn));
    not_empty_.notify_one();
  }
  void shutdown() override {
    {
      std::lock_guard<std::mutex> lock(mu_);
      shutdown_ = true;
    }
    not_empty_.notify_all();
    not_full_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

 private:
  void Work() {
    for (;;) {
      std::function<void()> fn;
      {
        std::unique_lock<std::mutex> lock(mu_);
        not_empty_.wait(lock, [&] { return !jobs_.empty() || shutdown_; });
        if (jobs_.empty()) return;  // shut down, nothing left
        fn = std::move(jobs_.front());
        jobs_.pop_front();
        not_full_.notify_one();
      }
      fn();
    }
  }
  const size_t capacity_;
  std::mutex mu_;
  std::condition_variable not_empty_, not_full_;
  std::deque<std::function<void()>> jobs_;
  std::vector<std::thread> threads_;
  bool shutdown_ = false;
};

// The state, its lock, and the rate-limited JSON built from it.
class Updates {
 public:
  explicit Updates(const ViewOptions& o)
      : options_(o),
        state_(o.channels, o.max_frames),
        gate_(std::chrono::duration_cast<Duration>(std::chrono::duration<double>(1.0 / o.rate_hz))),
        hub_(o.max_clients) {}

  void Ingest(const std::string& channel, const void* data, size_t size) {
    std::lock_guard<std::mutex> lock(mu_);
    state_.Ingest(channel, data, size, Now());
  }
  // Publishes a new update when something arrived since the last one and the rate allows.
  void MaybePublish() {
    std::string json;
    {
      std::lock_guard<std::mutex> lock(mu_);
      const Time now = Now();
      if (state_.version() == published_version_ || !gate_.Due(now)) return;
      published_version_ = state_.version();
      json = BuildViewJson(state_, now, options_.max_frames);
      ++built_;
      bytes_ += static_cast<int64_t>(json.size());
    }
    hub_.Publish(std::move(json));
  }
  // The page's data now (without the rate limit): for a request before anything arrived.
  std::string SnapshotNow() {
    std::lock_guard<std::mutex> lock(mu_);
    return BuildViewJson(state_, Now(), options_.max_frames);
  }
  std::string Status() {
    std::lock_guard<std::mutex> lock(mu_);
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "atlas-view: streams=%d messages=%lld rejected=%lld updates=%lld "
                  "update_bytes=%lld maps=%zu",
                  hub_.streams(), static_cast<long long>(state_.stored()),
                  static_cast<long long>(state_.rejected()), static_cast<long long>(built_),
                  static_cast<long long>(built_ > 0 ? bytes_ / built_ : 0), state_.maps().size());
    return buf;
  }
  SnapshotHub& hub() { return hub_; }

 private:
  const ViewOptions options_;
  std::mutex mu_;
  ViewState state_;
  RateGate gate_;
  uint64_t published_version_ = 0;
  int64_t built_ = 0, bytes_ = 0;
  SnapshotHub hub_;
};

void SetCommonHeaders(httplib::Response& res) {
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
}

// One event stream: the latest update at once, then each newer one; a comment line every 15 s
// of silence so that a vanished browser is noticed; ends when the hub stops.
struct StreamPosition {
  bool started = false;
  uint64_t seen = 0;
  Time last_write{};
};

bool StreamEvents(SnapshotHub& hub, StreamPosition& at, httplib::DataSink& sink) {
  std::shared_ptr<const std::string> update;
  if (!at.started) {
    at.started = true;
    at.last_write = Now();
    static constexpr char kRetry[] = "retry: 2000\n\n";
    if (!sink.write(kRetry, sizeof(kRetry) - 1)) return false;
    update = hub.Latest(&at.seen);
  }
  if (!update) update = hub.WaitNewer(&at.seen, std::chrono::seconds(1));
  if (hub.stopped()) return false;
  const Time now = Now();
  if (update) {
    std::string event;
    event.reserve(update->size() + 8);
    event += "data: ";
    event += *update;
    event += "\n\n";
    at.last_write = now;
    return sink.write(event.data(), event.size());
  }
  if (now - at.last_write > std::chrono::seconds(15)) {
    at.last_write = now;
    static constexpr char kKeepAlive[] = ": keep-alive\n\n";
    return sink.write(kKeepAlive, sizeof(kKeepAlive) - 1);
  }
  return true;
}

}  // namespace

int RunViewServer(const ViewOptions& o) {
  lcm::LCM lcm(o.lcm_url);
  if (!lcm.good()) {
    std::fprintf(stderr, "atlas-view: cannot open LCM %s (LCM_DEFAULT_URL, multicast route)\n",
                 o.lcm_url.empty() ? "(default URL)" : o.lcm_url.c_str());
    return 1;
  }
  Updates updates(o);
  struct Handler {
    Updates* updates;
    void Raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      updates->Ingest(channel, rbuf->data, rbuf->data_size);
    }
  } handler{&updates};
  for (const std::string* c : {&o.channels.pose, &o.channels.local_map, &o.channels.graph,
                               &o.channels.hypotheses, &o.channels.health})
    lcm.subscribe(*c, &Handler::Raw, &handler);

  httplib::Server server;
  const size_t workers = static_cast<size_t>(o.max_clients) + 2;
  server.new_task_queue = [workers] { return new BoundedTaskQueue(workers, 2 * workers); };
  server.set_read_timeout(5, 0);
  server.set_write_timeout(5, 0);
  server.set_payload_max_length(4096);
  server.set_keep_alive_max_count(20);
  server.set_keep_alive_timeout(2);  // an idle connection holds a worker thread
  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    SetCommonHeaders(res);
    // The page's script and style are inline; nothing may come from elsewhere.
    res.set_header("Content-Security-Policy",
                   "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                   "connect-src 'self'; img-src 'self'");
    const std::string_view page = ViewPage();
    res.set_content(page.data(), page.size(), "text/html; charset=utf-8");
  });
  server.Get("/snapshot.json", [&updates](const httplib::Request&, httplib::Response& res) {
    SetCommonHeaders(res);
    // The latest update (built within the rate limit): requests cannot make it build more often.
    updates.MaybePublish();
    uint64_t seq = 0;
    const std::shared_ptr<const std::string> latest = updates.hub().Latest(&seq);
    res.set_content(latest ? *latest : updates.SnapshotNow(), "application/json");
  });
  server.Get("/events", [&updates](const httplib::Request&, httplib::Response& res) {
    SetCommonHeaders(res);
    SnapshotHub& hub = updates.hub();
    if (!hub.TryOpenStream()) {
      res.status = 503;
      res.set_header("Retry-After", "10");
      res.set_content("atlas-view: too many viewers (--max-clients)\n", "text/plain");
      return;
    }
    auto at = std::make_shared<StreamPosition>();
    res.set_chunked_content_provider(
        "text/event-stream",
        [&hub, at](size_t, httplib::DataSink& sink) { return StreamEvents(hub, *at, sink); },
        [&hub](bool) { hub.CloseStream(); });
  });

  int port = o.port;
  if (port == 0) {
    port = server.bind_to_any_port(o.address);
  } else if (!server.bind_to_port(o.address, port)) {
    port = -1;
  }
  if (port <= 0) {
    std::fprintf(stderr, "atlas-view: cannot listen on %s port %d (in use? --address, --port)\n",
                 o.address.c_str(), o.port);
    return 1;
  }
  const bool v6 = o.address.find(':') != std::string::npos;
  std::fprintf(stderr,
               "atlas-view: serving http://%s%s%s:%d/ (LCM %s; at most %d viewers, %g updates/s)\n",
               v6 ? "[" : "", o.address.c_str(), v6 ? "]" : "", port,
               o.lcm_url.empty() ? "default URL" : o.lcm_url.c_str(), o.max_clients, o.rate_hz);

  std::atomic<bool> stop{false};
  std::thread http([&server] { server.listen_after_bind(); });
  std::thread lcm_thread([&] {
    while (!stop.load())
      if (lcm.handleTimeout(100) < 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  });
  std::thread update_thread([&] {
    const auto tick = std::chrono::duration<double>(1.0 / o.rate_hz) / 4;
    while (!stop.load()) {
      if (updates.hub().streams() > 0) updates.MaybePublish();
      std::this_thread::sleep_for(tick);
    }
  });

  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  Time next_status = Now() + FromSeconds(o.status_every_s).time_since_epoch();
  for (;;) {
    timespec wait{0, 200 * 1000 * 1000};
    const int sig = sigtimedwait(&signals, nullptr, &wait);
    if (sig == SIGINT || sig == SIGTERM) break;
    if (o.status_every_s > 0 && Now() >= next_status) {
      std::fprintf(stderr, "%s\n", updates.Status().c_str());
      next_status = Now() + FromSeconds(o.status_every_s).time_since_epoch();
    }
  }
  stop = true;
  updates.hub().Stop();
  server.stop();
  http.join();
  lcm_thread.join();
  update_thread.join();
  std::fprintf(stderr, "%s (stopped)\n", updates.Status().c_str());
  return 0;
}

}  // namespace atlas::view
