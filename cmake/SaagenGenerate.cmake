# saagen_generate(TARGET <name> MANIFEST <file> OUTPUT_DIR <dir>
#                 [TRADE_TABLE <file>] [OUTPUTS_VARIABLE <var>] [FORCE] [ALL])
#
# Runs `saagen emit --manifest <file> -o <dir>` as a build step and creates the custom target
# <name> for it. The files it writes (one per target and precision, e.g. saa_scene.glsl) are
# listed at configure time with `saagen emit --list-outputs`, returned in <var> and in the
# target's SAAGEN_OUTPUTS property: make the shader compilation depend on them.
#
# The step re-runs when the manifest, the trade table or the saagen executable changes, and not
# otherwise. saagen rewrites a file only when its bytes change, and the files are declared as
# byproducts of a stamp, so with Ninja (restat) nothing downstream rebuilds when a regeneration
# produced the same bytes. A change of the manifest also re-runs CMake (the list of files may
# change with it).
#
# Needs the imported executable saagen::cli, i.e. an installed saagen (find_package(saagen)):
# the file list is asked of it at configure time.
function(saagen_generate)
  cmake_parse_arguments(ARG "FORCE;ALL" "TARGET;MANIFEST;OUTPUT_DIR;TRADE_TABLE;OUTPUTS_VARIABLE" "" ${ARGN})
  foreach(required TARGET MANIFEST OUTPUT_DIR)
    if(NOT ARG_${required})
      message(FATAL_ERROR "saagen_generate: ${required} is required")
    endif()
  endforeach()
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "saagen_generate: unknown arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET saagen::cli)
    message(FATAL_ERROR "saagen_generate: no saagen::cli target; call find_package(saagen) first")
  endif()
  get_target_property(cli_imported saagen::cli IMPORTED)
  if(NOT cli_imported)
    message(FATAL_ERROR "saagen_generate: needs an installed saagen (find_package(saagen)), not saagen's own build tree")
  endif()

  get_filename_component(manifest "${ARG_MANIFEST}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_filename_component(output_dir "${ARG_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  set(extra_arguments "")
  set(extra_depends "")
  if(ARG_TRADE_TABLE)
    get_filename_component(trade_table "${ARG_TRADE_TABLE}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    list(APPEND extra_arguments --trade-table "${trade_table}")
    list(APPEND extra_depends "${trade_table}")
  endif()

  # The files, from the manifest (configure time); a manifest change re-runs this.
  get_target_property(saagen_executable saagen::cli LOCATION)
  execute_process(
    COMMAND "${saagen_executable}" emit --manifest "${manifest}" -o "${output_dir}" ${extra_arguments} --list-outputs
    OUTPUT_VARIABLE outputs
    ERROR_VARIABLE error
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    string(STRIP "${error}" error)
    message(FATAL_ERROR "saagen_generate(${ARG_TARGET}): ${error}")
  endif()
  string(STRIP "${outputs}" outputs)
  string(REPLACE "\n" ";" outputs "${outputs}")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${manifest}" ${extra_depends})

  if(ARG_FORCE)
    list(APPEND extra_arguments --force)
  endif()
  set(stamp "${CMAKE_CURRENT_BINARY_DIR}/${ARG_TARGET}.saagen-stamp")
  add_custom_command(
    OUTPUT "${stamp}"
    BYPRODUCTS ${outputs}
    COMMAND saagen::cli emit --manifest "${manifest}" -o "${output_dir}" ${extra_arguments}
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS "${manifest}" ${extra_depends} "$<TARGET_FILE:saagen::cli>"
    COMMENT "saagen: generating SAA snippets from ${ARG_MANIFEST}"
    VERBATIM)
  if(ARG_ALL)
    add_custom_target(${ARG_TARGET} ALL DEPENDS "${stamp}")
  else()
    add_custom_target(${ARG_TARGET} DEPENDS "${stamp}")
  endif()
  set_target_properties(${ARG_TARGET} PROPERTIES SAAGEN_OUTPUTS "${outputs}" SAAGEN_OUTPUT_DIR "${output_dir}")
  if(ARG_OUTPUTS_VARIABLE)
    set(${ARG_OUTPUTS_VARIABLE} "${outputs}" PARENT_SCOPE)
  endif()
endfunction()
