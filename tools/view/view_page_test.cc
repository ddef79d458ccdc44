#include "tools/view/view_page.h"

#include <gtest/gtest.h>

#include <string>

namespace atlas::view {
namespace {

TEST(ViewPage, IsOnePageThatListensToEvents) {
  const std::string page(ViewPage());
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("</html>"), std::string::npos);
  EXPECT_NE(page.find("<canvas id=\"canvas\">"), std::string::npos);
  EXPECT_NE(page.find("new EventSource(\"events\")"), std::string::npos);
  // The elements the browser test reads.
  for (const char* id : {"id=\"frames-drawn\"", "id=\"pose\"", "id=\"drivers\"", "id=\"updates\""})
    EXPECT_NE(page.find(id), std::string::npos) << id;
}

TEST(ViewPage, LoadsNothingFromElsewhere) {
  const std::string page(ViewPage());
  for (const char* external : {"http://", "https://", "//cdn", "<script src", "<link", "@import",
                               "url(", "@font-face", "fetch(\"http"})
    EXPECT_EQ(page.find(external), std::string::npos) << external;
}

}  // namespace
}  // namespace atlas::view
