# Writes the code version (project version + `git describe`) as a one-line header, and only
# when it changed: run at every build (target sphd_version), so results name the commit they
# were built from, and a commit recompiles one file (solver/run/code_version.cc) rather than
# every file that a compile definition would reach.
#   cmake -DSOURCE_DIR=... -DPROJECT_VERSION=... -DOUT=.../sphd_version.h -P write_version.cmake
execute_process(COMMAND git describe --always --dirty --tags
  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE described
  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
set(version "${PROJECT_VERSION}")
if(described)
  string(APPEND version "+${described}")
endif()
set(text "#define SPHD_VERSION \"${version}\"\n")
set(old "")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
