# Writes OUTPUT from INPUT (cmake/template_variants.hpp.in) with one row per `@variant` block of
# the template files TEMPLATES ("|"-separated), in file-name order as the catalogue reads them.
# Only the block lines matter: a block starts at a line `@constant`, `@variant` or `@function`
# (templates/README.md), and a variant's `path:` key sits in its block, before the next one.
string(REPLACE "|" ";" templates "${TEMPLATES}")
list(SORT templates)
set(rows "")
set(filters "")
set(count 0)

# A row of kTemplateVariants and, for a screen-space filter (forward-*, deferred-*: is_saa_filter
# in the header, which checks that both agree), an entry X(identifier, "id") of SAAGEN_SAA_FILTERS.
function(append_row id path file)
  if(path STREQUAL "")
    message(FATAL_ERROR "${file}: @variant ${id} has no path: key")
  endif()
  set(rows "${rows}    {\"${id}\", \"${path}\", \"${file}\"},\n" PARENT_SCOPE)
  if(id MATCHES "^(forward|deferred)-")
    string(REPLACE "-" "_" identifier ${id})
    set(filters "${filters}  X(${identifier}, \"${id}\") \\\n" PARENT_SCOPE)
  endif()
endfunction()

foreach(template IN LISTS templates)
  get_filename_component(file ${template} NAME)
  # Block headers and keys only: body lines are indented, and a `;` in them would split CMake's list.
  file(STRINGS ${template} lines REGEX "^(@[a-z]+ |path:)")
  set(id "")
  set(path "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^@")
      if(NOT id STREQUAL "")
        append_row("${id}" "${path}" "${file}")
        math(EXPR count "${count} + 1")
      endif()
      set(id "")
      set(path "")
      if(line MATCHES "^@variant +([A-Za-z0-9_-]+) *$")
        set(id ${CMAKE_MATCH_1})
      endif()
    elseif(NOT id STREQUAL "" AND line MATCHES "^path: *([a-z]+) *$")
      set(path ${CMAKE_MATCH_1})
    endif()
  endforeach()
  if(NOT id STREQUAL "")
    append_row("${id}" "${path}" "${file}")
    math(EXPR count "${count} + 1")
  endif()
endforeach()

set(SAAGEN_TEMPLATE_VARIANT_COUNT ${count})
set(SAAGEN_TEMPLATE_VARIANT_ROWS "${rows}")
set(SAAGEN_SAA_FILTER_ENTRIES "${filters}")
# configure_file writes only when the text changes: a template edit that adds no variant rebuilds nothing.
configure_file(${INPUT} ${OUTPUT} @ONLY)
