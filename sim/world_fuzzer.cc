// libFuzzer target: ParseWorld on arbitrary bytes must never crash, and whatever it accepts
// must round-trip through WriteWorld.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "sim/world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const atlas::sim::WorldParseResult r = atlas::sim::ParseWorld(in, "fuzz");
  if (!r.ok()) return 0;
  std::ostringstream out;
  atlas::sim::WriteWorld(out, r.world);
  std::istringstream again(out.str());
  const atlas::sim::WorldParseResult r2 = atlas::sim::ParseWorld(again, "fuzz-again");
  if (!r2.ok() || r2.world.walls.size() != r.world.walls.size() ||
      r2.world.nodes.size() != r.world.nodes.size() ||
      r2.world.edges.size() != r.world.edges.size())
    std::abort();
  return 0;
}
