#pragma once
// A ring of wide-beam ultrasonic transducers (Polaroid-like, as on the Pioneer P3-DX and the
// RWI B21).
//
// Each firing samples the beam cone with `rays_per_cone` rays. A ray whose wall it meets at an
// incidence angle (between the ray and the wall's normal) of at most `critical_incidence_deg`
// echoes straight back; the reported range is the nearest such echo in the cone (first return),
// plus Gaussian noise growing with range. When no ray in the cone echoes, the sound is
// reflected away (specular miss): with `multipath_probability` it comes back after one more
// bounce off another wall and the transducer reports the half path length (longer than the
// true range), otherwise, or if that exceeds the maximum range, it reports no return.
//
// The transducers fire in sequence; a reading carries those fired since the previous one, as a
// P2OS SIP does (docs/devices.md, section 3).

#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "sim/fast_noise.h"
#include "sim/ray_caster.h"

namespace atlas::sim {

// The 16 transducers of a Pioneer P3-DX (front and rear arrays of 8).
std::vector<SonarTransducer> P3dxSonarRing();
// 24 transducers evenly around a 0.26 m radius, like the RWI B21's ring.
std::vector<SonarTransducer> B21SonarRing();

struct SonarOptions {
  std::vector<SonarTransducer> ring = P3dxSonarRing();
  int rays_per_cone = 9;
  double critical_incidence_deg = 17.0;
  double multipath_probability = 0.4;
  double range_sigma = 0.01;         // m, at zero range
  double range_sigma_per_m = 0.01;   // m of sigma per m of range
  double reading_hz = 10.0;          // readings per second
  double firings_per_second = 40.0;  // transducers fired per second (all readings together)

  std::string Validate() const;
};

class SonarModel {
 public:
  SonarModel(const SonarOptions& options, uint64_t seed);
  // The range transducer `index` reports from the robot at `robot`: metres or kNoReturn.
  float Fire(const RayCaster& caster, const Pose2& robot, int index);
  // A reading with the transducers due since the last call, fired from `robot`.
  SonarReading Read(const RayCaster& caster, const Pose2& robot, Time stamp);

 private:
  SonarOptions o_;
  FastNoise noise_;
  double firing_credit_ = 0.0;
  int next_ = 0;
};

}  // namespace atlas::sim
