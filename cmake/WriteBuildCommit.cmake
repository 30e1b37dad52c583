# Run at every build (benchmarks/CMakeLists.txt, target build_commit): writes OUT, a header with
# DUET_BUILD_COMMIT = the commit of the source tree SOURCE_DIR as it is being built, "-dirty" when
# tracked files differ from it, "unknown" outside a git checkout. The file is rewritten only when
# that changes, so a build with nothing new recompiles nothing.
execute_process(COMMAND git -C "${SOURCE_DIR}" rev-parse HEAD
                OUTPUT_VARIABLE hash OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE failed ERROR_QUIET)
if(failed OR hash STREQUAL "")
  set(hash "unknown")
else()
  execute_process(COMMAND git -C "${SOURCE_DIR}" status --porcelain --untracked-files=no
                  OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT dirty STREQUAL "")
    string(APPEND hash "-dirty")
  endif()
endif()
set(text "#pragma once\n// Written by cmake/WriteBuildCommit.cmake at build time.\n#define DUET_BUILD_COMMIT \"${hash}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
