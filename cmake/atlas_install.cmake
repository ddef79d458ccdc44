# Install rules and the Debian package, included last by the top CMakeLists.txt.
#
#   cmake --install <build dir> [--prefix /usr]    installs what the package holds
#   (cd <build dir> && cpack)                      atlasd_<version>_<arch>.deb (CPack DEB)
#
# Tools are named by target: a folder that moves keeps its rules here. Targets the build does not
# have (the robot build, ATLAS_ROBOT, skips those needing Ceres, cairo or Java) are left out.
# The unit, the configuration and the udev and networkd examples are absolute system paths:
# the unit runs /usr/bin/atlasd, so install with the prefix /usr (the package does).
include(GNUInstallDirs)

# Every command-line tool, with the one-line summary its man page carries (help2man -n).
set(ATLAS_TOOLS
    "atlasd|real-time Atlas mapping daemon for mobile robots"
    "atlas-check-config|check an atlasd configuration file"
    "atlas-fakedev|fake SICK laser, P2OS sonar and AgileX CAN base playing a log"
    "atlas-sim|simulate a robot driving through a building"
    "atlas-carmen|read, count and convert CARMEN logs"
    "atlas-eval|score a trajectory against relations or a reference"
    "atlas-replay|run a CARMEN log through the Atlas as fast as it can"
    "atlas-refine|offline least-squares refinement of a saved atlas"
    "atlas-export|an atlas as g2o, TUM trajectory, PLY and a map_server occupancy grid"
    "atlas-render|draw a simulated run or an atlas (PNG, SVG)"
    "atlas-localmap-eval|consistency and accuracy of the local map"
    "atlas-sonar-eval|sonar-only local maps and atlas on the simulator"
    "atlas-lcm-log-summary|summarise an lcm-logger file of atlasd's channels"
    "atlas-pose-latency|latency of atlasd's published poses"
    "atlas-view|atlasd's live map in a web browser")

set(ATLAS_SYSTEMD_UNIT_DIR "" CACHE PATH "Where the systemd unit goes (default: systemd.pc's)")
if(NOT ATLAS_SYSTEMD_UNIT_DIR)
  pkg_get_variable(_atlas_unit_dir systemd systemdsystemunitdir)
  if(NOT _atlas_unit_dir)
    set(_atlas_unit_dir /lib/systemd/system)
  endif()
  set(ATLAS_SYSTEMD_UNIT_DIR ${_atlas_unit_dir})
endif()
set(ATLAS_PYTHON_DIR "lib/python3/dist-packages" CACHE STRING
    "Where the Python LCM types go, relative to the prefix")
set(_atlas_doc_dir ${CMAKE_INSTALL_DATADIR}/doc/atlasd)

# Man pages from each tool's --help (help2man), gzipped as Debian wants them.
find_program(HELP2MAN help2man)
if(NOT HELP2MAN)
  message(STATUS "help2man not found: no man pages (scripts/install-deps.sh installs it)")
endif()
set(_atlas_man_dir ${CMAKE_BINARY_DIR}/man)
set(_atlas_man_pages "")
# _atlas_man(NAME SECTION SUMMARY COMMAND DEPENDS): NAME.SECTION.gz in the build's man/.
function(_atlas_man name section summary command depends)
  set(page ${_atlas_man_dir}/${name}.${section})
  add_custom_command(
    OUTPUT ${page}.gz
    COMMAND ${CMAKE_COMMAND} -E make_directory ${_atlas_man_dir}
    COMMAND ${HELP2MAN} --no-info --section=${section} --name=${summary}
            --version-string=${PROJECT_VERSION} --output=${page} ${command}
    COMMAND gzip -9nf ${page}
    DEPENDS ${depends}
    COMMENT "help2man: ${name}.${section}"
    VERBATIM)
  set(_atlas_man_pages ${_atlas_man_pages} ${page}.gz PARENT_SCOPE)
  install(FILES ${page}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man${section})
endfunction()

set(_atlas_tool_targets "")
foreach(entry ${ATLAS_TOOLS})
  string(REPLACE "|" ";" entry "${entry}")
  list(GET entry 0 tool)
  list(GET entry 1 summary)
  if(NOT TARGET ${tool})
    continue()
  endif()
  list(APPEND _atlas_tool_targets ${tool})
  install(TARGETS ${tool} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  if(HELP2MAN)
    set(section 1)
    if(tool STREQUAL "atlasd")
      set(section 8)
    endif()
    _atlas_man(${tool} ${section} "${summary}" $<TARGET_FILE:${tool}> ${tool})
  endif()
endforeach()

# The message types: the .lcm sources, the C++ headers and Python modules lcm-gen made, and the
# Java jar with atlas-spy, which needs it.
install(FILES ${ATLAS_LCM_FILES} DESTINATION ${CMAKE_INSTALL_DATADIR}/atlasd/lcmtypes)
install(DIRECTORY ${ATLAS_LCM_CPP_DIR} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(DIRECTORY ${ATLAS_LCM_PYTHON_DIR} DESTINATION ${ATLAS_PYTHON_DIR}
        FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
if(TARGET atlas_lcmtypes_jar)
  # Debian's Java policy: the jar versioned, the plain name a symlink to it.
  install(FILES ${ATLAS_LCM_JAR} DESTINATION ${CMAKE_INSTALL_DATADIR}/java
          RENAME atlasd-lcmtypes-${PROJECT_VERSION}.jar)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/packaging)
  file(CREATE_LINK atlasd-lcmtypes-${PROJECT_VERSION}.jar
       ${CMAKE_BINARY_DIR}/packaging/atlasd-lcmtypes.jar SYMBOLIC)
  install(FILES ${CMAKE_BINARY_DIR}/packaging/atlasd-lcmtypes.jar
          DESTINATION ${CMAKE_INSTALL_DATADIR}/java)
  install(PROGRAMS ${CMAKE_SOURCE_DIR}/scripts/atlas-spy DESTINATION ${CMAKE_INSTALL_BINDIR})
  if(HELP2MAN)
    _atlas_man(atlas-spy 1 "lcm-spy with atlasd's message types"
               ${CMAKE_SOURCE_DIR}/scripts/atlas-spy ${CMAKE_SOURCE_DIR}/scripts/atlas-spy)
  endif()
endif()
add_custom_target(atlas_man ALL DEPENDS ${_atlas_man_pages})

# Every tool and the jar, without the tests (scripts/demo.sh builds this).
add_custom_target(atlas_tools)
add_dependencies(atlas_tools ${_atlas_tool_targets} atlas_lcmtypes_python)
if(TARGET atlas_lcmtypes_jar)
  add_dependencies(atlas_tools atlas_lcmtypes_jar)
endif()

# The service, its configuration (a conffile of the package) and the documents.
install(FILES ${CMAKE_SOURCE_DIR}/systemd/atlasd.service DESTINATION ${ATLAS_SYSTEMD_UNIT_DIR})
install(FILES ${CMAKE_SOURCE_DIR}/config/atlasd.toml DESTINATION /etc/atlasd)
install(FILES ${CMAKE_SOURCE_DIR}/README.md ${CMAKE_SOURCE_DIR}/docs/atlasd.md
              ${CMAKE_SOURCE_DIR}/docs/config.md ${CMAKE_SOURCE_DIR}/docs/lcm.md
              ${CMAKE_SOURCE_DIR}/docs/atlas-view.md ${CMAKE_SOURCE_DIR}/docs/systemd.md
        DESTINATION ${_atlas_doc_dir})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/config/robot/ DESTINATION ${_atlas_doc_dir}/examples)
install(FILES ${CMAKE_SOURCE_DIR}/config/atlasd-fakedev.toml
        DESTINATION ${_atlas_doc_dir}/examples)

# Debian's copyright file and changelog (packaging/deb/), and the package's maintainer.
set(CPACK_PACKAGE_CONTACT
    "atlasd maintainers <maintainers@users.noreply.h-seed-80565290.example>"
    CACHE STRING "The package's Maintainer field")
set(_atlas_deb_dir ${CMAKE_SOURCE_DIR}/packaging/deb)
configure_file(${_atlas_deb_dir}/changelog.in ${CMAKE_BINARY_DIR}/packaging/changelog.Debian @ONLY)
add_custom_command(
  OUTPUT ${CMAKE_BINARY_DIR}/packaging/changelog.Debian.gz
  COMMAND gzip -9nkf ${CMAKE_BINARY_DIR}/packaging/changelog.Debian
  DEPENDS ${CMAKE_BINARY_DIR}/packaging/changelog.Debian
  COMMENT "gzip: changelog.Debian")
add_custom_target(atlas_deb_changelog ALL DEPENDS ${CMAKE_BINARY_DIR}/packaging/changelog.Debian.gz)
install(FILES ${_atlas_deb_dir}/copyright ${CMAKE_BINARY_DIR}/packaging/changelog.Debian.gz
        DESTINATION ${_atlas_doc_dir})
# Lintian's overrides for what a package built outside Debian's archive cannot avoid.
install(FILES ${_atlas_deb_dir}/lintian-overrides DESTINATION ${CMAKE_INSTALL_DATADIR}/lintian/overrides
        RENAME atlasd)

# CPack DEB. Run-time dependencies come from the binaries (dpkg-shlibdeps), and python3;
# atlas-spy's Java ones are recommended.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME atlasd)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time mapping daemon for mobile robots (Atlas)")
set(_atlas_deb_jar "")
if(TARGET atlas_lcmtypes_jar)
  set(_atlas_deb_jar " and a Java jar")
endif()
set(CPACK_PACKAGE_DESCRIPTION
    "atlasd maps with a laser scanner, sonar and wheel odometry in real time.\n"
    "It implements the Atlas framework (Bosse, Newman, Leonard, Teller): a graph\n"
    "of small local map frames instead of one global map, so that the work per\n"
    "sensor update stays constant however large the mapped region grows. It\n"
    "publishes pose, local map, atlas graph and health on LCM, runs under systemd\n"
    "(sd_notify, watchdog) and saves its atlas to SQLite.\n"
    "The package also holds the offline tools, the fake devices, and the LCM\n"
    "message types as .lcm files, C++ headers, Python modules${_atlas_deb_jar}.")
string(REPLACE ";" "" CPACK_PACKAGE_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# Debian revision 1 of the upstream version: the changelog is changelog.Debian.gz.
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python modules of the message types.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3:any")
if(TARGET atlas_lcmtypes_jar)
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
      "default-jre | java-runtime, liblcm-java, libjchart2d-java")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "liblcm-bin, liblcm-dev")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
configure_file(${_atlas_deb_dir}/conffiles ${CMAKE_BINARY_DIR}/packaging/conffiles COPYONLY)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${CMAKE_BINARY_DIR}/packaging/conffiles ${_atlas_deb_dir}/postinst ${_atlas_deb_dir}/prerm
    ${_atlas_deb_dir}/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
