# tessim_rtl_list(<out-var> <list-file>): the SystemVerilog sources a list file names
# (rtl/tess.f, rtl/system.f, rtl/ge/ge.f), as absolute paths in its order: the one reader of
# those lists in CMake (scripts read them with scripts/rtl_sources.py, the same rules). One source
# a line, relative to the list's directory; lines are stripped, blank lines and lines starting with
# // skipped. Editing the list re-runs CMake.
function(tessim_rtl_list out listing)
  if(NOT EXISTS ${listing})
    message(FATAL_ERROR "${listing}: the list of RTL sources is missing")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${listing})
  get_filename_component(dir ${listing} DIRECTORY)
  file(STRINGS ${listing} lines)
  set(sources "")
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    if(line STREQUAL "" OR line MATCHES "^//")
      continue()
    endif()
    get_filename_component(src ${dir}/${line} ABSOLUTE)
    if(NOT EXISTS ${src})
      message(FATAL_ERROR "${listing}: '${line}' does not exist")
    endif()
    list(APPEND sources ${src})
  endforeach()
  if(NOT sources)
    message(FATAL_ERROR "${listing} lists no sources")
  endif()
  set(${out} ${sources} PARENT_SCOPE)
endfunction()

# tessim_rtl_sources(<out-var> <dir>): the unit's sources, <dir>/tess.f (the package first, then
# the modules), which the Verilated builds, lint and synthesis read.
function(tessim_rtl_sources out dir)
  tessim_rtl_list(sources ${dir}/tess.f)
  set(${out} ${sources} PARENT_SCOPE)
endfunction()
