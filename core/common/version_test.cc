#include "core/common/version.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
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
  std::smatch m;
  const std::string cmake = text.str();
  ASSERT_TRUE(std::regex_search(cmake, m, std::regex(R"(project\(atlasd VERSION ([0-9.]+))")));
  const std::string v = AtlasVersion();
  EXPECT_TRUE(std::regex_match(v, std::regex(m[1].str() + R"(( \(git [^ ()]+\))?)"))) << v;
  EXPECT_EQ(VersionLine("atlasd"), "atlasd " + v + "\n");
}

}  // namespace
}  // namespace atlas
