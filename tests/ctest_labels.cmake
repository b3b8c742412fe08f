# Included by ctest (TEST_INCLUDE_FILES, after catch_discover_tests' list of cases): gives every case
# of the Catch binary LABEL_EXECUTABLE its labels, from `--list-tests -v high`, which prints per
# case its name (indented 2, a long one continued indented 4), its source file:line and
# description (4) and its tags (6):
#   - the folder of tests/ its source is in: gl, exec, memory, scene, shadow, image, cli, docs,
#     extremes, differential, support;
#   - its kind: golden (tagged [golden...]), oracle (tagged [...oracle...]), differential (its
#     folder), cli (its folder), else unit;
#   - slow when tagged [slow]: the few cases that take seconds even without a sanitizer; the
#     sanitizer run leaves them to the Release run (scripts/test.sh --sanitize).
#   - conformance when tagged [conformance]: compared with Mesa, as tests/conformance is.
execute_process(COMMAND "${LABEL_EXECUTABLE}" --list-tests -v high
                OUTPUT_VARIABLE listing ERROR_QUIET)
if(NOT listing MATCHES "test cases:")  # Catch's exit status is the number of cases
  return()
endif()
# CMake lists split at ';' and treat brackets specially: both are masked while splitting lines.
string(REPLACE ";" "<semicolon>" listing "${listing}")
string(REPLACE "[" "<open>" listing "${listing}")
string(REPLACE "]" "<close>" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
# Labels the case just read (its tags line is optional).
macro(label_case)
  if(NOT name STREQUAL "")
    set(labels "${folder}")
    if(tags MATCHES "<open>golden")
      list(APPEND labels golden)
    elseif(tags MATCHES "oracle")
      list(APPEND labels oracle)
    elseif(NOT folder STREQUAL "differential" AND NOT folder STREQUAL "cli")
      list(APPEND labels unit)
    endif()
    if(tags MATCHES "<open>slow<close>")
      list(APPEND labels slow)
    endif()
    if(tags MATCHES "<open>conformance<close>")
      list(APPEND labels conformance)  # against Mesa, as tests/conformance
    endif()
    list(REMOVE_ITEM labels "")
    string(REPLACE "<open>" "[" name "${name}")
    string(REPLACE "<close>" "]" name "${name}")
    set_tests_properties("${LABEL_PREFIX}${name}" PROPERTIES LABELS "${labels}")
  endif()
  set(name "")
  set(folder "")
  set(tags "")
  set(seen_file FALSE)
endmacro()
set(name "")
set(folder "")
set(seen_file FALSE)
foreach(line IN LISTS lines)
  if(line MATCHES "^  ([^ ].*)$")
    set(next "${CMAKE_MATCH_1}")  # label_case's own matches overwrite CMAKE_MATCH_1
    label_case()
    set(name "${next}")
  elseif(line MATCHES "^    [^ ].*:[0-9]+$")
    set(seen_file TRUE)
    if(line MATCHES "tests/([a-z_]+)/[^/ ]+:[0-9]+$")
      set(folder "${CMAKE_MATCH_1}")
    endif()
  elseif(line MATCHES "^    ([^ ].*)$" AND NOT seen_file AND NOT name STREQUAL "")
    string(APPEND name " ${CMAKE_MATCH_1}")  # a name too long for one line, wrapped at a space
  elseif(line MATCHES "^      (<open>.*)$")
    set(tags "${CMAKE_MATCH_1}")
  endif()
endforeach()
label_case()
