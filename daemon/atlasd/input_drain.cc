#include "daemon/atlasd/input_drain.h"

#include <utility>

#include "core/mapper/step_loop.h"

namespace atlas {

InputDrain::InputDrain(SpscQueue<OdometrySample>* odometry, SpscQueue<SonarReading>* sonar,
                       SpscQueue<LaserScan>* laser)
    : odometry_(odometry), sonar_(sonar), laser_(laser) {
  if (sonar_) readings_.reserve(sonar_->capacity());
  if (laser_) scans_.reserve(laser_->capacity());
}

void InputDrain::Drain(DrainTarget* target) {
  OdometrySample o;
  while (odometry_ && odometry_->Pop(&o)) {
    target->OnOdometry(o);
  }
  readings_.clear();
  scans_.clear();
  SonarReading s;
  while (sonar_ && readings_.size() < readings_.capacity() && sonar_->Pop(&s)) {
    readings_.push_back(std::move(s));
  }
  LaserScan scan;
  while (laser_ && scans_.size() < scans_.capacity() && laser_->Pop(&scan)) {
    scans_.push_back(std::move(scan));
  }
  InStampOrder(
      readings_, scans_, [&](SonarReading& r) { target->OnSonar(r); },
      [&](LaserScan& l) { target->OnScan(l); });
}

}  // namespace atlas
