#pragma once
// atlasd's version: the project version of CMakeLists.txt, and in a git checkout what
// `git describe --tags --always --dirty` said at build time, e.g. "0.1.0 (git 990180e-dirty)".
// Every tool prints it for --version, atlasd at start-up and in its health message. Defined in
// a file generated at build time (cmake/atlas_version.cmake), never on a compile line.

#include <string>

namespace atlas {

const char* AtlasVersion();

// "<tool> <AtlasVersion()>\n": what --version prints on stdout.
inline std::string VersionLine(const char* tool) {
  return std::string(tool) + " " + AtlasVersion() + "\n";
}

}  // namespace atlas
