#include "drivers/fake/sent_record.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace atlas::fake {
namespace {

TEST(SentRecordTest, KeepsTheLastItemsInOrderAndCountsAll) {
  SentRecord<int> r(4);
  for (int i = 0; i < 3; ++i) r.Add(i);
  EXPECT_EQ(r.Items(), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(r.total(), 3u);
  EXPECT_EQ(r.dropped(), 0u);
  for (int i = 3; i < 10; ++i) r.Add(i);  // two laps and a half of the ring
  EXPECT_EQ(r.Items(), (std::vector<int>{6, 7, 8, 9}));
  EXPECT_EQ(r.total(), 10u);
  EXPECT_EQ(r.dropped(), 6u);
  EXPECT_EQ(r.capacity(), 4u);
}

TEST(SentRecordTest, StaysBoundedOverManyItems) {
  SentRecord<std::string> r(3);
  for (int i = 0; i < 100000; ++i) r.Add(std::to_string(i));
  EXPECT_EQ(r.Items(), (std::vector<std::string>{"99997", "99998", "99999"}));
  EXPECT_EQ(r.total(), 100000u);
  EXPECT_EQ(r.dropped(), 99997u);
}

TEST(SentRecordTest, CapacityZeroOnlyCounts) {
  SentRecord<int> r(0);
  for (int i = 0; i < 5; ++i) r.Add(i);
  EXPECT_TRUE(r.Items().empty());
  EXPECT_EQ(r.total(), 5u);
  EXPECT_EQ(r.dropped(), 5u);
}

}  // namespace
}  // namespace atlas::fake
