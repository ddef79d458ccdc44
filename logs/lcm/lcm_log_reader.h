#pragma once
// The one reader of lcm-logger files, shared by `atlasd --replay` and atlas-lcm-log-summary, so
// that a bad file is refused the same way by both (docs/formats.md "LCM logs").
//
// LCM's own reader (lcm::LogFile) cannot tell the end of a log from a problem in it: it skips
// any bytes up to the next sync word (so a directory, an empty file, random bytes or a CARMEN
// text log read as a log of 0 events), stops without a word at an incomplete last event, and
// stops at a corrupt event after printing "Log event has invalid channel length". This reader
// checks the format (lcm/eventlog.c, big-endian): every event is
//   int32 sync word 0xEDA1DA01, int64 event number, int64 timestamp (us),
//   int32 channel length (1..1000), int32 data length (>= 0), channel, data
// one after the other from byte 0, and says what is wrong and where:
//   Open():  not a regular file, cannot be opened, empty, does not begin with the sync word;
//   Next():  false at the end of the log; problem() is then empty, or says that the log is
//            truncated (the last event is incomplete: the events before it were read) or
//            corrupt (no sync word where the next event begins, or an impossible length: the
//            events before it were read, none after it).
// Decode() counts the events that do not decode as the type asked for (undecodable()).
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace atlas {

inline constexpr uint32_t kLcmLogSyncWord = 0xEDA1DA01;

struct LcmLogEvent {
  int64_t offset = 0;  // byte of the file where the event begins
  int64_t eventnum = 0;
  int64_t timestamp = 0;  // us (lcm-logger: receive time)
  std::string channel;
  std::vector<uint8_t> data;
};

class LcmLogReader {
 public:
  LcmLogReader() = default;
  LcmLogReader(const LcmLogReader&) = delete;
  LcmLogReader& operator=(const LcmLogReader&) = delete;
  ~LcmLogReader();

  // False with error() set when `path` cannot be read as an LCM log.
  bool Open(const std::string& path);
  // The next event, or false at the end of the log or at a problem (problem()).
  bool Next(LcmLogEvent* event);

  // Decodes `event` as M (an lcm-gen type); false, counted in undecodable(), when it is not one.
  template <class M>
  bool Decode(const LcmLogEvent& event, M* m) {
    if (m->decode(event.data.data(), 0, static_cast<int>(event.data.size())) >= 0) return true;
    ++undecodable_[event.channel];
    return false;
  }

  // Why Open() failed: "PATH: what, what to do".
  const std::string& error() const { return error_; }
  // After Next() returned false: empty when the whole log was read, else what stopped the
  // reading ("PATH: truncated at byte N: ..." or "PATH: corrupt at byte N: ...").
  const std::string& problem() const { return problem_; }
  bool truncated() const { return truncated_; }
  int64_t events() const { return events_; }
  // Bytes of the file read so far, and its size (for progress).
  int64_t bytes_read() const { return pos_; }
  int64_t size() const { return size_; }
  // Events that Decode() could not decode, by channel.
  const std::map<std::string, int64_t>& undecodable() const { return undecodable_; }
  int64_t undecodable_total() const;
  // Every problem of the reading so far (the truncation or corruption, and the undecodable
  // events by channel), one message each; empty when there is none.
  std::vector<std::string> Problems() const;

 private:
  bool Fail(const std::string& what);
  bool Stop(bool truncated, int64_t at, const std::string& what);
  // Reads n bytes at the current position; false (nothing consumed beyond the file) at the end.
  bool Read(void* out, size_t n);

  std::string path_;
  std::FILE* file_ = nullptr;
  int64_t size_ = 0, pos_ = 0, events_ = 0;
  bool done_ = false, truncated_ = false;
  std::string error_, problem_;
  std::map<std::string, int64_t> undecodable_;
};

}  // namespace atlas
