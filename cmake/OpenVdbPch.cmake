# A precompiled <openvdb/openvdb.h> for the sources that reach it.
#
# A source that sees OpenVDB's grids spends about half of its compile
# parsing them (oracles/minimum.cpp: 9.6 CPU-s at -O3, 4.2 s with the header
# precompiled; plugins/lighting_vpl_deferred/vpl.cpp: 10.2 s, 5.4 s). A
# source that does not would pay for loading the header and for OpenVDB's
# inline code instead (core/base/error.cpp: 0.8 s, 4.3 s with it). So only
# the sources that reach OpenVDB beyond its small math headers get it: found
# at configure time from the project's own #include "..." lines, followed
# through the headers. A source whose includes change keeps its old choice
# until the next configure; that costs time, never correctness.
#
# The header is compiled once for weft_core and reused by the libraries
# built with the same flags; a test executable with enough such sources
# compiles its own. ccache caches sources compiled with it given
# CCACHE_SLOPPINESS=pch_defines,time_macros (CMakeLists.txt sets that).
option(WEFT_PCH "Precompile <openvdb/openvdb.h> for the sources that include OpenVDB's grids" ON)

# OpenVDB headers that stay cheap without a precompiled header.
set(_WEFT_LIGHT_OPENVDB "^openvdb/math/(Vec[234]|Coord|BBox|Mat|Mat[34]|Math)\\.h$")

# Sets `result` to TRUE when `file` includes a heavy OpenVDB header,
# directly or through the project's headers. Answers are kept per file.
function(_weft_reaches_openvdb file result)
  get_property(known GLOBAL PROPERTY "WEFT_OPENVDB_${file}" SET)
  if(known)
    get_property(answer GLOBAL PROPERTY "WEFT_OPENVDB_${file}")
    set(${result} ${answer} PARENT_SCOPE)
    return()
  endif()
  set_property(GLOBAL PROPERTY "WEFT_OPENVDB_${file}" FALSE)  # an include cycle ends here
  file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
  set(answer FALSE)
  foreach(line IN LISTS lines)
    if(line MATCHES "<(openvdb/[^>]+)>")
      if(NOT CMAKE_MATCH_1 MATCHES "${_WEFT_LIGHT_OPENVDB}")
        set(answer TRUE)
        break()
      endif()
    elseif(line MATCHES "\"([^\"]+)\"" AND EXISTS "${CMAKE_SOURCE_DIR}/${CMAKE_MATCH_1}")
      _weft_reaches_openvdb("${CMAKE_SOURCE_DIR}/${CMAKE_MATCH_1}" included)
      if(included)
        set(answer TRUE)
        break()
      endif()
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY "WEFT_OPENVDB_${file}" ${answer})
  set(${result} ${answer} PARENT_SCOPE)
endfunction()

# Gives `target`'s sources that reach OpenVDB the precompiled header:
# weft_core's own, reused by the other libraries; an executable's own.
function(weft_precompile_openvdb target)
  if(NOT WEFT_PCH)
    return()
  endif()
  get_target_property(sources ${target} SOURCES)
  get_target_property(source_dir ${target} SOURCE_DIR)
  set(reaching 0)
  foreach(source IN LISTS sources)
    get_filename_component(path "${source}" ABSOLUTE BASE_DIR "${source_dir}")
    set(reaches FALSE)
    if(EXISTS "${path}")  # generated sources do not exist yet
      _weft_reaches_openvdb("${path}" reaches)
    endif()
    if(reaches)
      math(EXPR reaching "${reaching} + 1")
    else()
      set_source_files_properties("${source}" TARGET_DIRECTORY ${target} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
    endif()
  endforeach()
  # An executable compiles with -fPIE, where weft_core's header has -fPIC:
  # GCC would refuse that one, so an executable precompiles its own.
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE" AND reaching LESS 4)
    return()  # its header would cost more than it saves (about 20 s against 5 s a source)
  endif()
  if(target STREQUAL "weft_core" OR type STREQUAL "EXECUTABLE")
    target_precompile_headers(${target} PRIVATE <openvdb/openvdb.h>)
  else()
    target_precompile_headers(${target} REUSE_FROM weft_core)
  endif()
endfunction()
