#include "logs/lcm/lcm_log_reader.h"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstring>

namespace atlas {
namespace {

constexpr int64_t kHeaderBytes = 4 + 8 + 8 + 4 + 4;
constexpr int32_t kMaxChannelLength = 1000;  // lcm/eventlog.c refuses 1000 and more

uint64_t BigEndian(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

std::string Hex(const uint8_t* p, size_t n) {
  std::string s;
  char b[4];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(b, sizeof b, "%s%02X", i ? " " : "", p[i]);
    s += b;
  }
  return s;
}

std::string Plural(int64_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

LcmLogReader::~LcmLogReader() {
  if (file_ != nullptr) std::fclose(file_);
}

bool LcmLogReader::Fail(const std::string& what) {
  error_ = path_ + ": " + what;
  done_ = true;
  return false;
}

bool LcmLogReader::Stop(bool truncated, int64_t at, const std::string& what) {
  truncated_ = truncated;
  problem_ = path_ + ": " + (truncated ? "truncated" : "corrupt") + " at byte " +
             std::to_string(at) + ": " + what + "; " +
             (events_ == 0   ? std::string("no event before it")
              : events_ == 1 ? std::string("the event before it was read")
                             : "the " + std::to_string(events_) + " events before it were read") +
             (truncated ? "" : ", none after it");
  done_ = true;
  return false;
}

bool LcmLogReader::Open(const std::string& path) {
  path_ = path;
  struct stat st {};
  if (stat(path.c_str(), &st) != 0)
    return Fail(std::string("cannot read the LCM log (") + std::strerror(errno) + ")");
  if (S_ISDIR(st.st_mode))
    return Fail("is a directory, not an LCM log: give the file that lcm-logger wrote");
  if (!S_ISREG(st.st_mode))
    return Fail(
        "is not a regular file (a device, FIFO or socket): give the file that "
        "lcm-logger wrote");
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr)
    return Fail(std::string("cannot open the LCM log (") + std::strerror(errno) + ")");
  size_ = static_cast<int64_t>(st.st_size);
  if (size_ == 0)
    return Fail("is empty, not an LCM log (lcm-logger recorded nothing, or wrote elsewhere)");
  uint8_t head[16] = {};
  const size_t n = std::fread(head, 1, sizeof head, file_);
  if (n >= 4 && BigEndian(head, 4) == kLcmLogSyncWord) {
    std::rewind(file_);
    return true;
  }
  std::string what = "not an LCM log: it begins with " + Hex(head, std::min<size_t>(n, 4)) +
                     ", not with the sync word ED A1 DA 01 that begins every event of an "
                     "lcm-logger file";
  bool text = n > 0;
  for (size_t i = 0; i < n; ++i) text = text && (std::isprint(head[i]) || std::isspace(head[i]));
  if (text) {
    std::string start(reinterpret_cast<const char*>(head), n);
    for (char& c : start)
      if (std::isspace(static_cast<unsigned char>(c))) c = ' ';
    what += " (it begins with text, \"" + start + "\": a CARMEN log? atlas-replay reads those)";
  }
  return Fail(what);
}

bool LcmLogReader::Read(void* out, size_t n) { return std::fread(out, 1, n, file_) == n; }

bool LcmLogReader::Next(LcmLogEvent* event) {
  if (done_ || file_ == nullptr) return false;
  const int64_t start = pos_, left = size_ - pos_;
  if (left == 0) {
    done_ = true;
    return false;
  }
  uint8_t h[kHeaderBytes];
  const size_t got = std::fread(h, 1, static_cast<size_t>(std::min(left, kHeaderBytes)), file_);
  if (std::ferror(file_))
    return Stop(false, start, std::string("read error (") + std::strerror(errno) + ")");
  const std::string which =
      "event " + std::to_string(events_ + 1) + " (from byte " + std::to_string(start) + ")";
  const size_t sync_bytes = std::min<size_t>(got, 4);
  uint8_t sync[4];
  for (size_t i = 0; i < 4; ++i) sync[i] = static_cast<uint8_t>(kLcmLogSyncWord >> (24 - 8 * i));
  if (std::memcmp(h, sync, sync_bytes) != 0)
    return Stop(false, start,
                which + " does not begin with the sync word ED A1 DA 01 (found " +
                    Hex(h, sync_bytes) + ")");
  if (static_cast<int64_t>(got) < kHeaderBytes)
    return Stop(true, size_,
                "the last event, " + which + ", is incomplete: its header needs " +
                    std::to_string(kHeaderBytes) + " bytes, the file ends after " +
                    std::to_string(got));
  const int32_t channel_length = static_cast<int32_t>(BigEndian(h + 20, 4));
  const int32_t data_length = static_cast<int32_t>(BigEndian(h + 24, 4));
  if (channel_length <= 0 || channel_length >= kMaxChannelLength)
    return Stop(false, start,
                which + " has an invalid channel length " + std::to_string(channel_length) +
                    " (1 to " + std::to_string(kMaxChannelLength - 1) + ")");
  if (data_length < 0)
    return Stop(false, start, which + " has a negative data length " + std::to_string(data_length));
  const int64_t body = int64_t{channel_length} + data_length;
  if (body > left - kHeaderBytes)
    return Stop(true, size_,
                "the last event, " + which + ", is incomplete: it needs " +
                    std::to_string(kHeaderBytes + body) + " bytes, the file ends after " +
                    std::to_string(left));
  event->offset = start;
  event->eventnum = static_cast<int64_t>(BigEndian(h + 4, 8));
  event->timestamp = static_cast<int64_t>(BigEndian(h + 12, 8));
  event->channel.resize(static_cast<size_t>(channel_length));
  event->data.resize(static_cast<size_t>(data_length));
  if (!Read(event->channel.data(), event->channel.size()) ||
      !Read(event->data.data(), event->data.size())) {
    if (std::ferror(file_))
      return Stop(false, start, std::string("read error (") + std::strerror(errno) + ")");
    return Stop(true, start, "the file became shorter while it was read");
  }
  pos_ = start + kHeaderBytes + body;
  ++events_;
  return true;
}

int64_t LcmLogReader::undecodable_total() const {
  int64_t n = 0;
  for (const auto& [channel, count] : undecodable_) n += count;
  return n;
}

std::vector<std::string> LcmLogReader::Problems() const {
  std::vector<std::string> problems;
  if (!problem_.empty()) problems.push_back(problem_);
  for (const auto& [channel, count] : undecodable_)
    problems.push_back(path_ + ": " + Plural(count, "event") + " on " + channel +
                       " could not be decoded as that channel's type (another lcmtypes "
                       "version, or damaged data) and " +
                       (count == 1 ? "was" : "were") + " left out");
  return problems;
}

}  // namespace atlas
