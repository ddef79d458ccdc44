#include "tools/sonar_eval/world_option.h"

#include <cstdint>

#include "sim/building_generator.h"

namespace atlas::sonar_eval {

std::string SelectWorld(const std::string& name, int seed, int rooms, const AlcoveLoopOptions& loop,
                        sim::World* world) {
  if (name == "building") {
    sim::BuildingOptions bo;
    bo.min_rooms = static_cast<int>(rooms);
    *world = sim::GenerateBuilding(bo, static_cast<uint64_t>(seed));
    return "";
  }
  if (name == "alcoves") {
    if (std::string e = loop.Validate(); !e.empty()) return "alcove loop: " + e;
    *world = AlcoveLoopWorld(loop);
    return "";
  }
  return "--world must be 'building' or 'alcoves', not '" + name + "'";
}

}  // namespace atlas::sonar_eval
