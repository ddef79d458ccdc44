#include "core/atlas/map_matcher.h"

#include <optional>

namespace atlas {
namespace {

class WholeMatch final : public MapMatchSearch {
 public:
  WholeMatch(const MapMatcher& matcher, const UncertainPose* prior) : matcher_(matcher) {
    if (prior != nullptr) prior_ = *prior;
  }
  bool Continue(const LocalMap& a, const LocalMap& b) override {
    if (!done_) result_ = matcher_.Match(a, b, prior_ ? &*prior_ : nullptr);
    done_ = true;
    return true;
  }
  const MapMatch& Result() const override { return result_; }

 private:
  const MapMatcher& matcher_;
  std::optional<UncertainPose> prior_;
  bool done_ = false;
  MapMatch result_;
};

}  // namespace

std::unique_ptr<MapMatchSearch> MapMatcher::Begin(const LocalMap&, const LocalMap&,
                                                  const UncertainPose* prior) const {
  return std::make_unique<WholeMatch>(*this, prior);
}

}  // namespace atlas
