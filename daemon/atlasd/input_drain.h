#pragma once
// One drain of the device queues by the live loop thread (live_daemon.h): the odometry first,
// then the sonar readings and laser scans taken together, handed on in stamp order
// (InStampOrder, step_loop.h: a scan before a reading of the same stamp), so that the loop
// steps them, and a recording of the raw channels holds them, in that order. Stamps are handed
// on as the drivers made them (the StepLoop truncates them to the raw channels' resolution:
// StepLoopOptions::stamp_resolution). At most one queue's
// capacity of readings and of scans per drain; the buffers are reserved at construction, so a
// drain does not allocate.

#include <vector>

#include "core/common/sensor_types.h"
#include "drivers/queue/spsc_queue.h"

namespace atlas {

// Where a drain hands what it took, one item at a time, in order.
class DrainTarget {
 public:
  virtual ~DrainTarget() = default;
  virtual void OnOdometry(const OdometrySample& sample) = 0;
  virtual void OnSonar(SonarReading& reading) = 0;  // may move from `reading`
  virtual void OnScan(LaserScan& scan) = 0;         // may move from `scan`
};

class InputDrain {
 public:
  // A null queue is a device that is not enabled. The queues outlive the drain.
  InputDrain(SpscQueue<OdometrySample>* odometry, SpscQueue<SonarReading>* sonar,
             SpscQueue<LaserScan>* laser);

  void Drain(DrainTarget* target);

 private:
  SpscQueue<OdometrySample>* odometry_;
  SpscQueue<SonarReading>* sonar_;
  SpscQueue<LaserScan>* laser_;
  std::vector<SonarReading> readings_;  // one drain, capacity reserved
  std::vector<LaserScan> scans_;
};

}  // namespace atlas
