# Third-party libraries, linked statically.
#
# acommsd runs on vehicle computers that are rarely updated in step with the
# distribution, so every third-party library is linked in: `ldd acommsd` must
# show only the C library family. Debian ships the static archives (.a); this
# file turns them into INTERFACE targets named acomms::<lib>. The shared
# libraries that the Debian CMake configs would pick are deliberately avoided.

find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)

# Libraries that glibc provides (or that are merged into libc since 2.34):
# linked dynamically, they add nothing beyond libc/libm to ldd.
set(_ACOMMS_SYSTEM_LIBS m dl rt pthread)

# acomms_static_archives(<out-var> <lib-name>...) resolves each name to its .a
function(acomms_static_archives out)
  set(paths "")
  foreach(name IN LISTS ARGN)
    if(name IN_LIST _ACOMMS_SYSTEM_LIBS)
      list(APPEND paths "${name}")
      continue()
    endif()
    if(name STREQUAL "atomic")
      # libatomic.a lives in gcc's private directory, not the multiarch one.
      execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libatomic.a
                      OUTPUT_VARIABLE archive OUTPUT_STRIP_TRAILING_WHITESPACE)
    else()
      find_library(ACOMMS_STATIC_${name} NAMES lib${name}.a NO_CACHE)
      set(archive "${ACOMMS_STATIC_${name}}")
    endif()
    if(NOT archive OR NOT EXISTS "${archive}")
      message(FATAL_ERROR "static archive lib${name}.a not found: "
                          "run packaging/install-deps.sh")
    endif()
    list(APPEND paths "${archive}")
  endforeach()
  set(${out} "${paths}" PARENT_SCOPE)
endfunction()

# acomms_static_target(<target> LIBS <names...> [DEFINES ...] [INCLUDES ...])
function(acomms_static_target target)
  cmake_parse_arguments(ARG "" "" "LIBS;DEFINES" ${ARGN})
  acomms_static_archives(archives ${ARG_LIBS})
  add_library(${target} INTERFACE IMPORTED GLOBAL)
  # A group lets the linker resolve the circular references between gRPC,
  # abseil and upb archives without hand-ordering them.
  target_link_libraries(${target} INTERFACE
    -Wl,--start-group ${archives} -Wl,--end-group Threads::Threads)
  if(ARG_DEFINES)
    target_compile_definitions(${target} INTERFACE ${ARG_DEFINES})
  endif()
endfunction()

# pkg-config knows gRPC's transitive static dependencies (abseil, upb, re2,
# c-ares, OpenSSL, zlib); its order is kept.
function(acomms_pkg_static_libs out module)
  execute_process(COMMAND ${PKG_CONFIG_EXECUTABLE} --static --libs-only-l ${module}
                  OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config ${module} failed: run packaging/install-deps.sh")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  set(names "")
  foreach(flag IN LISTS flags)
    string(REGEX REPLACE "^-l" "" name "${flag}")
    list(APPEND names ${name})
  endforeach()
  list(REMOVE_DUPLICATES names)
  set(${out} "${names}" PARENT_SCOPE)
endfunction()

acomms_static_target(acomms::protobuf LIBS protobuf z)
acomms_static_target(acomms::protoc LIBS protoc protobuf z)
acomms_pkg_static_libs(_grpc_libs grpc++)
acomms_static_target(acomms::grpc LIBS grpc++_reflection ${_grpc_libs} protobuf)
acomms_static_target(acomms::cryptopp LIBS cryptopp)
acomms_static_target(acomms::sqlite3 LIBS sqlite3 m dl)
# WGS84 <-> local metres for position telemetry's datum (daemon/telemetry).
acomms_static_target(acomms::geographiclib LIBS GeographicLib)

# Header-only libraries. spdlog and Asio are compiled once each, by
# cmake/CompiledOnce.cmake (included once the tree's compile options are set).
add_library(acomms::cli11 INTERFACE IMPORTED GLOBAL)
# Eigen (the telemetry Kalman filter) lives under include/eigen3/, not on the
# default include path.
find_path(ACOMMS_EIGEN3_INCLUDE_DIR Eigen/Core PATH_SUFFIXES eigen3 REQUIRED)
add_library(acomms::eigen INTERFACE IMPORTED GLOBAL)
target_include_directories(acomms::eigen SYSTEM INTERFACE "${ACOMMS_EIGEN3_INCLUDE_DIR}")

find_program(ACOMMS_PROTOC protoc REQUIRED)
find_program(ACOMMS_GRPC_CPP_PLUGIN grpc_cpp_plugin REQUIRED)

# Flags for the two shipped executables: the C++ runtime goes in statically too.
function(acomms_static_executable target)
  target_link_options(${target} PRIVATE -static-libstdc++ -static-libgcc -Wl,--as-needed)
endfunction()
