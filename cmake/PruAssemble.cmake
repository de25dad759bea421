# pru_assemble_image(NAME <name> SOURCE <file.p> [DEFINES NAME[=value] ...]
#                    [INCLUDES <dir> ...] [CORE <1|2|3>])
#
# Assembles a pasm-dialect source into ${CMAKE_CURRENT_BINARY_DIR}/<name>.bin
# (a raw little-endian IRAM image) and adds a target <name> that builds it.
# The assembler is the project's pruasm unless the cache variable
# BISS_FW_ASSEMBLER is "pasm", then TI's pasm (PASM_EXECUTABLE) is used with
# the same flags. The image path is stored in the target property IMAGE_FILE.
# <name> is also the output base name, so it must not contain '.'.
function(pru_assemble_image)
  cmake_parse_arguments(A "" "NAME;SOURCE;CORE" "DEFINES;INCLUDES" ${ARGN})
  if(NOT A_NAME OR NOT A_SOURCE)
    message(FATAL_ERROR "pru_assemble_image: NAME and SOURCE are required")
  endif()
  if(A_NAME MATCHES "\\.")
    message(FATAL_ERROR "pru_assemble_image: NAME '${A_NAME}' must not contain '.'")
  endif()
  if(NOT A_CORE)
    set(A_CORE 3)
  endif()
  get_filename_component(src "${A_SOURCE}" ABSOLUTE)
  get_filename_component(srcdir "${src}" DIRECTORY)

  if(BISS_FW_ASSEMBLER STREQUAL "pasm")
    if(NOT PASM_EXECUTABLE)
      message(FATAL_ERROR "BISS_FW_ASSEMBLER=pasm but no pasm was found (set PASM_EXECUTABLE)")
    endif()
    set(tool "${PASM_EXECUTABLE}")
    set(tool_dep "")
  elseif(BISS_FW_ASSEMBLER STREQUAL "pruasm" OR NOT BISS_FW_ASSEMBLER)
    set(tool "${BISS_PRUASM}") # cmake/NativeTools.cmake
    set(tool_dep ${BISS_PRUASM_DEP})
  else()
    message(FATAL_ERROR "BISS_FW_ASSEMBLER must be pruasm or pasm, not '${BISS_FW_ASSEMBLER}'")
  endif()

  set(flags -V${A_CORE} -b)
  foreach(d IN LISTS A_DEFINES)
    list(APPEND flags "-D${d}")
  endforeach()
  # Files the source may include (the firmware's parts, pru_fw/README.md):
  # rebuild when any of them changes, and re-glob when one is added.
  file(GLOB deps CONFIGURE_DEPENDS "${srcdir}/*.hp" "${srcdir}/*.h" "${srcdir}/*.p")
  foreach(i IN LISTS A_INCLUDES)
    get_filename_component(i "${i}" ABSOLUTE)
    list(APPEND flags "-I${i}")
    file(GLOB more "${i}/*.hp" "${i}/*.h")
    list(APPEND deps ${more})
  endforeach()

  set(out "${CMAKE_CURRENT_BINARY_DIR}/${A_NAME}.bin")
  add_custom_command(
    OUTPUT "${out}"
    COMMAND "${tool}" ${flags} "${src}" "${A_NAME}"
    WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
    DEPENDS "${src}" ${deps} ${tool_dep}
    COMMENT "Assembling ${A_NAME}.bin with ${BISS_FW_ASSEMBLER}"
    VERBATIM)
  add_custom_target(${A_NAME} ALL DEPENDS "${out}")
  set_target_properties(${A_NAME} PROPERTIES IMAGE_FILE "${out}")
endfunction()
