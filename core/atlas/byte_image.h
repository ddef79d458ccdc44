#pragma once
// Little-endian byte images for Atlas::Serialize (no I/O: strings in memory). A reader never
// reads past the end: every Get returns false instead, and the caller rejects the image.
// Values are copied as the host holds them (memcpy), which is little-endian on every host
// atlasd is built for; PutArray and GetArray copy a block of values at once, the same bytes as
// Put and Get of each value in turn.

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "core/geometry/se2.h"

namespace atlas {

class ByteWriter {
 public:
  template <typename T>
  void Put(T v) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void PutArray(const T* values, size_t n) {
    static_assert(std::is_arithmetic_v<T>);
    out_.append(reinterpret_cast<const char*>(values), n * sizeof(T));
  }
  void PutString(const std::string& s) {
    Put<uint64_t>(s.size());
    out_.append(s);
  }
  void PutPose(const Pose2& p) {
    Put(p.x);
    Put(p.y);
    Put(p.theta);
  }
  void PutMat3(const Mat3& m) {
    for (int i = 0; i < 9; ++i) Put(m.data()[i]);
  }
  void PutUncertain(const UncertainPose& p) {
    PutPose(p.mean);
    PutMat3(p.cov);
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& s) : s_(s) {}
  template <typename T>
  bool Get(T* v) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    if (s_.size() - at_ < sizeof(T)) return false;
    std::memcpy(v, s_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  // All n values or none (false: fewer bytes are left).
  template <typename T>
  bool GetArray(T* values, size_t n) {
    static_assert(std::is_arithmetic_v<T>);
    if ((s_.size() - at_) / sizeof(T) < n) return false;
    std::memcpy(values, s_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return true;
  }
  bool GetString(std::string* out, uint64_t max_size) {
    uint64_t n = 0;
    if (!Get(&n) || n > max_size || s_.size() - at_ < n) return false;
    out->assign(s_.data() + at_, n);
    at_ += n;
    return true;
  }
  bool GetPose(Pose2* p) { return Get(&p->x) && Get(&p->y) && Get(&p->theta); }
  bool GetMat3(Mat3* m) {
    for (int i = 0; i < 9; ++i)
      if (!Get(&m->data()[i])) return false;
    return true;
  }
  bool GetUncertain(UncertainPose* p) { return GetPose(&p->mean) && GetMat3(&p->cov); }
  bool AtEnd() const { return at_ == s_.size(); }

 private:
  const std::string& s_;
  size_t at_ = 0;
};

}  // namespace atlas
