# acomms_proto_library(<target> ROOT <dir> PROTOS <relative .proto paths> [GRPC] [DEPENDS <targets>])
#
# Generates C++ for .proto files (paths relative to ROOT, so imports read
# "acomms/v1/config.proto") into the build tree, and builds them as one
# static library.
function(acomms_proto_library target)
  cmake_parse_arguments(ARG "GRPC" "ROOT" "PROTOS;DEPENDS;IMPORT_DIRS" ${ARGN})
  set(out_dir "${CMAKE_BINARY_DIR}/generated")
  file(MAKE_DIRECTORY "${out_dir}")
  set(import_flags "-I${ARG_ROOT}")
  foreach(dir IN LISTS ARG_IMPORT_DIRS)
    list(APPEND import_flags "-I${dir}")
  endforeach()
  set(srcs "")
  foreach(proto IN LISTS ARG_PROTOS)
    string(REGEX REPLACE "\\.proto$" "" stem "${proto}")
    set(outputs "${out_dir}/${stem}.pb.cc" "${out_dir}/${stem}.pb.h")
    set(plugin_args "")
    if(ARG_GRPC)
      list(APPEND outputs "${out_dir}/${stem}.grpc.pb.cc" "${out_dir}/${stem}.grpc.pb.h")
      set(plugin_args "--grpc_out=${out_dir}"
                      "--plugin=protoc-gen-grpc=${ACOMMS_GRPC_CPP_PLUGIN}")
    endif()
    add_custom_command(
      OUTPUT ${outputs}
      COMMAND ${ACOMMS_PROTOC} ${import_flags} "--cpp_out=${out_dir}" ${plugin_args}
              "${ARG_ROOT}/${proto}"
      DEPENDS "${ARG_ROOT}/${proto}" ${ACOMMS_PROTOC}
      COMMENT "protoc ${proto}"
      VERBATIM)
    list(APPEND srcs ${outputs})
  endforeach()
  add_library(${target} STATIC ${srcs})
  target_include_directories(${target} PUBLIC "${out_dir}")
  target_link_libraries(${target} PUBLIC acomms::protobuf ${ARG_DEPENDS})
  if(ARG_GRPC)
    target_link_libraries(${target} PUBLIC acomms::grpc)
  endif()
  # Generated code is not ours to lint.
  set_target_properties(${target} PROPERTIES CXX_CLANG_TIDY "")
endfunction()

# acomms_embed_text(<target> NAMESPACE <ns> TABLE <function> FILES <abs paths>)
# Builds a static library whose one function returns {file name, text} for each file.
function(acomms_embed_text target)
  cmake_parse_arguments(ARG "" "NAMESPACE;TABLE" "FILES" ${ARGN})
  set(out "${CMAKE_CURRENT_BINARY_DIR}/${target}.cpp")
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} "-DOUTPUT=${out}" "-DINPUTS=${ARG_FILES}"
            "-DNAMESPACE=${ARG_NAMESPACE}" "-DTABLE=${ARG_TABLE}"
            -P "${CMAKE_SOURCE_DIR}/cmake/EmbedText.cmake"
    DEPENDS ${ARG_FILES} "${CMAKE_SOURCE_DIR}/cmake/EmbedText.cmake"
    COMMENT "embedding ${target}"
    VERBATIM)
  add_library(${target} STATIC "${out}")
endfunction()
