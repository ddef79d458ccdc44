#include "core/common/quote_for_message.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

TEST(QuoteForMessage, ShowsAtMost40BytesAndEscapesTheRest) {
  EXPECT_EQ(QuoteForMessage("ab\n"), "'ab\\x0a'");
  EXPECT_EQ(QuoteForMessage(std::string_view("a\tb", 3)), "'a\\x09b'");
  EXPECT_EQ(QuoteForMessage(std::string(50, 'x')), "'" + std::string(40, 'x') + "'...");
}

}  // namespace
}  // namespace atlas
