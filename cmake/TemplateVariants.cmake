# saagen_template_variants(OUTPUT header TEMPLATES file...)
# Generates the registry of the templates' variants: a header listing every `@variant` block of
# TEMPLATES (id, path, template file, in the catalogue's file-name order), from
# cmake/template_variants.hpp.in. The code that iterates over variants (the renderer's rows, the
# tests of the registry) reads it instead of a hand-written list, so that a variant is declared
# once, in its template. Regenerated at build time when a template changes.
set(SAAGEN_TEMPLATE_VARIANTS_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/TemplateVariantsScript.cmake)
set(SAAGEN_TEMPLATE_VARIANTS_IN ${CMAKE_CURRENT_LIST_DIR}/template_variants.hpp.in)

function(saagen_template_variants)
  cmake_parse_arguments(ARG "" "OUTPUT" "TEMPLATES" ${ARGN})
  string(REPLACE ";" "|" templates_arg "${ARG_TEMPLATES}")
  add_custom_command(
    OUTPUT ${ARG_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} -DINPUT=${SAAGEN_TEMPLATE_VARIANTS_IN}
            "-DTEMPLATES=${templates_arg}" -P ${SAAGEN_TEMPLATE_VARIANTS_SCRIPT}
    DEPENDS ${ARG_TEMPLATES} ${SAAGEN_TEMPLATE_VARIANTS_SCRIPT} ${SAAGEN_TEMPLATE_VARIANTS_IN}
    COMMENT "Listing the templates' variants"
    VERBATIM)
endfunction()
