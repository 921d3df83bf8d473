# How the build stays short on CI's two cores (figures: the README's
# "Building by hand"). Two means, each applied from one place so that no test
# folder has to remember it:
#
# - Test code is compiled at -O1 (acomms_test_optimisation). Tests spend their
#   time in the libraries they link, which keep the build type's flags; -O3
#   on GoogleTest's macro-heavy units cost a third more compile time for
#   nothing a test measures. Benchmarks keep the build type's flags.
# - Precompiled headers where parsing, not optimising, is the cost: for test
#   code, GoogleTest, GoogleMock, protobuf and the standard library,
#   precompiled once (acomms_test_pch) and reused by every target that links
#   GoogleTest (a test unit: 7.6 s -> 3.3 s with -O1); for the gRPC API's two
#   big users (acommsctl, the service), the API's generated headers
#   (acomms_api_pch: a command's unit 10.3 s -> 5.4 s). Measured and left
#   out: gRPC's own headers alone gave the -O3 product units nothing, and a
#   shared PCH made units that do not use it slower. A header in a shared
#   PCH must not depend on a macro that differs between the targets sharing
#   it: only third-party and standard headers go in, and -Winvalid-pch
#   reports a PCH the compiler refused.

# Every target defined in DIR and the folders below it.
function(acomms_targets_below dir out)
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    acomms_targets_below("${sub}" below)
    list(APPEND targets ${below})
  endforeach()
  set(${out} "${targets}" PARENT_SCOPE)
endfunction()

# True when TARGET compiles C++ with the optimisation its folder gives it
# (a target with its own -O, like the telemetry debug-build check, keeps it).
function(_acomms_own_optimisation target out)
  get_target_property(options ${target} COMPILE_OPTIONS)
  set(own FALSE)
  if(options)
    list(FILTER options INCLUDE REGEX "^-O")
    list(LENGTH options count)
    get_directory_property(dir_options COMPILE_OPTIONS)
    list(FILTER dir_options INCLUDE REGEX "^-O")
    list(LENGTH dir_options dir_count)
    if(count GREATER dir_count)
      set(own TRUE)
    endif()
  endif()
  set(${out} ${own} PARENT_SCOPE)
endfunction()

# acomms_precompile(PCH_TARGET HEADERS <h>... LINK <libs>...): an object
# library that only builds a PCH of HEADERS, with the flags of LINK's users.
function(acomms_precompile pch_target)
  cmake_parse_arguments(ARG "" "" "HEADERS;LINK" ${ARGN})
  set(anchor "${CMAKE_CURRENT_BINARY_DIR}/${pch_target}_anchor.cpp")
  if(NOT EXISTS "${anchor}")
    file(WRITE "${anchor}" "// Only here so that ${pch_target} has a unit; its PCH is what others reuse.\n")
  endif()
  add_library(${pch_target} OBJECT "${anchor}")
  target_link_libraries(${pch_target} PRIVATE ${ARG_LINK})
  target_precompile_headers(${pch_target} PRIVATE ${ARG_HEADERS})
  target_compile_options(${pch_target} PRIVATE -Winvalid-pch)
endfunction()

# Every target below DIR that links one of LINKED reuses PCH_TARGET's PCH.
function(acomms_reuse_pch_below dir pch_target)
  cmake_parse_arguments(ARG "" "" "LINKED" ${ARGN})
  acomms_targets_below("${dir}" targets)
  foreach(target IN LISTS targets)
    if(target STREQUAL pch_target)
      continue()
    endif()
    get_target_property(type ${target} TYPE)
    if(NOT type MATCHES "^(EXECUTABLE|STATIC_LIBRARY|OBJECT_LIBRARY)$")
      continue()
    endif()
    get_target_property(libs ${target} LINK_LIBRARIES)
    set(links FALSE)
    foreach(lib IN LISTS ARG_LINKED)
      if(libs AND lib IN_LIST libs)
        set(links TRUE)
      endif()
    endforeach()
    _acomms_own_optimisation(${target} own)
    if(links AND NOT own)
      target_precompile_headers(${target} REUSE_FROM ${pch_target})
      target_compile_options(${target} PRIVATE -Winvalid-pch)
    endif()
  endforeach()
endfunction()

# acomms_api_pch(TARGET [WITH <header>...]): TARGET precompiles the gRPC API's
# generated headers (and WITH), for its own units only.
function(acomms_api_pch target)
  cmake_parse_arguments(ARG "" "" "WITH" ${ARGN})
  target_precompile_headers(${target} PRIVATE
    <grpcpp/grpcpp.h> [["acomms/v1/acomms.grpc.pb.h"]] [["acomms/v1/gram.grpc.pb.h"]]
    [["acomms/v1/config.pb.h"]] ${ARG_WITH})
  target_compile_options(${target} PRIVATE -Winvalid-pch)
endfunction()
