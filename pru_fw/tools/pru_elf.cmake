# pru-elf: writes the raw firmware image as the ELF remoteproc loads, with
# elfutils' libelf (PkgConfig::LIBELF). Included by pru_fw/ and by the
# build-machine tools of a cross build (cmake/native-tools).
set(_src ${CMAKE_CURRENT_LIST_DIR}/../..)
add_executable(pru-elf ${CMAKE_CURRENT_LIST_DIR}/pru_elf.c ${_src}/host/biss_image_id.c
  ${_src}/emulator/util/safe_file.c)
target_include_directories(pru-elf PRIVATE ${_src}/host ${_src}/include ${_src}/emulator/util)
target_link_libraries(pru-elf PRIVATE PkgConfig::LIBELF)
