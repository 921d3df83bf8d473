# Files built into a binary as byte arrays, so that it needs none of them
# installed where it runs (the map's page and Leaflet in acommsctl).
#
# acomms_embed_files(OUTPUT out.cpp HEADER "geov/assets.h" FUNCTION embedded_assets
#   NAMESPACE acomms::cli::geov FILES "/url|mime type|/path/to/file" ...)
# generates out.cpp defining `const std::vector<EmbeddedFile>& FUNCTION()`
# (EmbeddedFile as declared in HEADER: name, type, bytes); it is generated
# again when a listed file changes.
set(ACOMMS_EMBED_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/EmbedFilesScript.cmake")

function(acomms_embed_files)
  cmake_parse_arguments(EMBED "" "OUTPUT;HEADER;FUNCTION;NAMESPACE" "FILES" ${ARGN})
  set(manifest "${EMBED_OUTPUT}.manifest")
  set(depends)
  set(lines)
  foreach(entry IN LISTS EMBED_FILES)
    string(REPLACE "|" ";" parts "${entry}")
    list(GET parts 2 path)
    if(NOT EXISTS "${path}")
      message(FATAL_ERROR "acomms_embed_files: ${path} is missing (packaging/install-deps.sh installs it)")
    endif()
    list(APPEND depends "${path}")
    string(APPEND lines "${entry}\n")
  endforeach()
  file(GENERATE OUTPUT "${manifest}" CONTENT "${lines}")
  add_custom_command(OUTPUT "${EMBED_OUTPUT}"
    COMMAND "${CMAKE_COMMAND}" -DMANIFEST=${manifest} -DOUTPUT=${EMBED_OUTPUT} -DHEADER=${EMBED_HEADER}
            -DFUNCTION=${EMBED_FUNCTION} -DNAMESPACE=${EMBED_NAMESPACE} -P "${ACOMMS_EMBED_SCRIPT}"
    DEPENDS ${depends} "${manifest}" "${ACOMMS_EMBED_SCRIPT}"
    COMMENT "Embedding ${EMBED_FUNCTION} into ${EMBED_OUTPUT}"
    VERBATIM)
endfunction()
