# pru-elf: writes the raw firmware image as the ELF remoteproc loads, with
# elfutils' libelf (PkgConfig::LIBELF). Included by pru_fw/ and by the
# build-machine tools of a cross build (cmake/native-tools).
set(_src ${CMAKE_CURRENT_LIST_DIR}/../..)
# The identification block is proto's (proto/biss_image_id.c), the safe
# writer common's: compiled in, so pru-elf needs neither library.
add_executable(pru-elf ${CMAKE_CURRENT_LIST_DIR}/pru_elf.c ${_src}/proto/biss_image_id.c
  ${_src}/common/safe_file.c)
target_include_directories(pru-elf PRIVATE ${_src}/proto ${_src}/include ${_src}/common)
target_link_libraries(pru-elf PRIVATE PkgConfig::LIBELF)
