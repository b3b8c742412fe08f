# shadowref_split_by_include(SOURCES MATCHED REGEX): moves the files of the list SOURCES whose text
# matches REGEX (an #include line) into the list MATCHED. A library whose include brings a heavy
# dependency (cpp-httplib, OpenImageIO) is kept out of the programs and tests that do not need it
# by the include itself, so a new file lands on the right side without a list to keep by hand.
function(shadowref_split_by_include sources_var matched_var regex)
  set(kept)
  set(matched)
  foreach(source IN LISTS ${sources_var})
    file(STRINGS ${source} hit REGEX "${regex}" LIMIT_COUNT 1)
    if(hit)
      list(APPEND matched ${source})
    else()
      list(APPEND kept ${source})
    endif()
  endforeach()
  set(${sources_var} ${kept} PARENT_SCOPE)
  set(${matched_var} ${matched} PARENT_SCOPE)
endfunction()
