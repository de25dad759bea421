# The tools the build itself runs: pruasm (assembles the firmware) and
# pru-elf (writes its remoteproc ELF). Sets
#   BISS_PRUASM, BISS_PRU_ELF   the commands to run
#   BISS_PRUASM_DEP, BISS_PRU_ELF_DEP   the targets those commands need
# A native build runs its own targets. A cross build cannot run what it
# builds, so it takes them from BISS_NATIVE_TOOLS_DIR (a native build tree,
# or any directory holding both) or, by default, builds them for the build
# machine with the build machine's compiler (cmake/native-tools, an external
# project in <build>/native-tools).
if(NOT CMAKE_CROSSCOMPILING)
  set(BISS_PRUASM $<TARGET_FILE:pruasm>)
  set(BISS_PRU_ELF $<TARGET_FILE:pru-elf>)
  set(BISS_PRUASM_DEP pruasm)
  set(BISS_PRU_ELF_DEP pru-elf)
  return()
endif()

set(BISS_NATIVE_TOOLS_DIR "" CACHE PATH
    "Cross builds: directory with build-machine pruasm and pru-elf (empty: build them)")
if(BISS_NATIVE_TOOLS_DIR)
  foreach(tool pruasm pru-elf)
    if(NOT EXISTS ${BISS_NATIVE_TOOLS_DIR}/${tool})
      message(FATAL_ERROR "BISS_NATIVE_TOOLS_DIR: no ${tool} in ${BISS_NATIVE_TOOLS_DIR}")
    endif()
  endforeach()
  set(BISS_PRUASM ${BISS_NATIVE_TOOLS_DIR}/pruasm)
  set(BISS_PRU_ELF ${BISS_NATIVE_TOOLS_DIR}/pru-elf)
  set(BISS_PRUASM_DEP "")
  set(BISS_PRU_ELF_DEP "")
  return()
endif()

include(ExternalProject)
set(dir ${PROJECT_BINARY_DIR}/native-tools)
# No toolchain file is passed on: the child uses the build machine's compiler
# (and its own pkg-config search path, for libelf).
ExternalProject_Add(native_tools
  SOURCE_DIR ${PROJECT_SOURCE_DIR}/cmake/native-tools
  BINARY_DIR ${dir}
  CMAKE_ARGS -DCMAKE_BUILD_TYPE=Release -DBISS_VERSION=${PROJECT_VERSION}
  BUILD_ALWAYS ON
  INSTALL_COMMAND ""
  BUILD_BYPRODUCTS ${dir}/pruasm ${dir}/pru-elf)
set(BISS_PRUASM ${dir}/pruasm)
set(BISS_PRU_ELF ${dir}/pru-elf)
set(BISS_PRUASM_DEP native_tools)
set(BISS_PRU_ELF_DEP native_tools)
