# Writes OUTPUT, a header defining SHADOWREF_REVISION: the short commit hash of SOURCE_DIR, with
# "-dirty" when tracked files differ from it, or "unknown" when SOURCE_DIR is not the top of a git
# work tree (a tarball, or no git installed). Runs on every build (cmake -P); the header is written
# only when its text changes, so an unchanged revision recompiles nothing.
#   cmake -DSOURCE_DIR=<dir> -DOUTPUT=<file> -P write_revision.cmake
set(revision unknown)
find_program(GIT_EXECUTABLE git)
if(GIT_EXECUTABLE)
  # Only the tree's own repository: a source tree unpacked inside another one is not from git.
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" rev-parse --show-toplevel
                  OUTPUT_VARIABLE top RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(rc EQUAL 0)
    file(REAL_PATH "${top}" top)
    file(REAL_PATH "${SOURCE_DIR}" source)
  endif()
  if(rc EQUAL 0 AND top STREQUAL source)
    # --exclude=*: the hash even where tags exist, so the revision always names one commit.
    execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" describe --always --dirty --exclude=*
                    OUTPUT_VARIABLE described RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(rc EQUAL 0 AND described MATCHES "^[0-9a-f]+(-dirty)?$")
      set(revision "${described}")
    endif()
  endif()
endif()

set(text "// Generated on every build by cmake/write_revision.cmake.\n#pragma once\n#define SHADOWREF_REVISION \"${revision}\"\n")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
