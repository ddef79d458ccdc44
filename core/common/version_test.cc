#include "core/common/version.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "atlas_paths.h"

namespace atlas {
namespace {

// The version of project() in CMakeLists.txt leads; a git checkout adds what git describe said.
TEST(VersionTest, IsTheProjectVersionAndTheCommit) {
  std::ifstream in(std::string(ATLAS_SOURCE_DIR) + "/CMakeLists.txt");
  std::stringstream text;
  text << in.rdbuf();
  const std::string cmake = text.str();
  const std::string key = "project(atlasd VERSION ";
  const size_t at = cmake.find(key);
  ASSERT_NE(at, std::string::npos);
  const size_t start = at + key.size();
  const std::string project =
      cmake.substr(start, cmake.find_first_not_of("0123456789.", start) - start);
  ASSERT_FALSE(project.empty());
  const std::string v = AtlasVersion();
  ASSERT_EQ(v.substr(0, project.size()), project) << v;
  // Nothing more, or " (git DESCRIPTION)" without spaces or parentheses inside.
  const std::string rest = v.substr(project.size());
  if (!rest.empty()) {
    ASSERT_GT(rest.size(), 7u) << v;
    EXPECT_EQ(rest.substr(0, 6), " (git ") << v;
    EXPECT_EQ(rest.back(), ')') << v;
    EXPECT_EQ(rest.find_first_of(" ()", 6), rest.size() - 1) << v;
  }
  EXPECT_EQ(VersionLine("atlasd"), "atlasd " + v + "\n");
}

}  // namespace
}  // namespace atlas
