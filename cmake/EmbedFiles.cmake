# saagen_embed_files(OUTPUT file NAMESPACE ns ROOT dir FILES f...)
# Generates a C++ source that holds each file's bytes, keyed by its path relative to ROOT, so
# the installed CLI and library need no data directory. Regenerated when an input changes.
set(SAAGEN_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedFilesScript.cmake)

function(saagen_embed_files)
  cmake_parse_arguments(ARG "" "OUTPUT;NAMESPACE;ROOT;FILES_VARIABLE" "FILES" ${ARGN})
  string(REPLACE ";" "|" files_arg "${ARG_FILES}")
  add_custom_command(
    OUTPUT ${ARG_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} -DNAMESPACE=${ARG_NAMESPACE}
            -DROOT=${ARG_ROOT} "-DFILES=${files_arg}" -P ${SAAGEN_EMBED_SCRIPT}
    DEPENDS ${ARG_FILES} ${SAAGEN_EMBED_SCRIPT}
    COMMENT "Embedding templates and target tables"
    VERBATIM)
endfunction()
