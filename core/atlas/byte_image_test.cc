#include "core/atlas/byte_image.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

namespace atlas {
namespace {

// A block written at once is the same bytes as one Put per value, and reads back as one Get
// per value; a block longer than what is left is not read, and nothing is consumed.
TEST(ByteImage, ArraysAreTheBytesOfOnePutPerValue) {
  const std::vector<uint16_t> values = {0, 1, 0x7fff, 0x1234, 0xfffe};
  ByteWriter each, block;
  each.Put<uint8_t>(7);
  block.Put<uint8_t>(7);
  for (uint16_t v : values) each.Put(v);
  block.PutArray(values.data(), values.size());
  EXPECT_EQ(block.bytes(), each.bytes());
  // As the host holds them: little-endian on every host atlasd is built for.
  if constexpr (std::endian::native == std::endian::little) {
    EXPECT_EQ(block.bytes().substr(7, 2), std::string("\x34\x12", 2));
  }

  const std::string bytes = block.bytes();
  ByteReader r(bytes);
  uint8_t head = 0;
  ASSERT_TRUE(r.Get(&head));
  std::vector<uint16_t> too_many(values.size() + 1);
  EXPECT_FALSE(r.GetArray(too_many.data(), too_many.size()));
  std::vector<uint16_t> read(values.size());
  ASSERT_TRUE(r.GetArray(read.data(), read.size()));
  EXPECT_EQ(read, values);
  EXPECT_TRUE(r.AtEnd());
  EXPECT_TRUE(r.GetArray(read.data(), 0));
}

}  // namespace
}  // namespace atlas
