# Cross-building for the ARM of a BeagleBone / AM437x board (hard float):
#   cmake -S . -B build-arm -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-armhf.cmake \
#         -DBUILD_TESTING=OFF
# Debian: gcc-arm-linux-gnueabihf (and qemu-user to run the result on a PC).
# The build-machine tools the firmware step runs (pruasm, pru-elf) are built
# natively by cmake/NativeTools.cmake.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(BISS_CROSS_TRIPLE arm-linux-gnueabihf CACHE STRING "GNU triple of the cross compiler")
set(CMAKE_C_COMPILER ${BISS_CROSS_TRIPLE}-gcc)

# Libraries and headers from the target's side only; programs from the
# build machine.
set(CMAKE_FIND_ROOT_PATH /usr/${BISS_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# pkg-config: the target's .pc files (Debian multiarch, e.g. libcjson-dev:armhf),
# never the build machine's.
set(ENV{PKG_CONFIG_LIBDIR}
    /usr/lib/${BISS_CROSS_TRIPLE}/pkgconfig:/usr/${BISS_CROSS_TRIPLE}/lib/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")

# Runs ARM programs on the build machine (tests, try_run): qemu-user.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-arm -L /usr/${BISS_CROSS_TRIPLE})
# Large inode numbers on 64-bit hosts (sysfs, qemu): readdir must not fail
# with EOVERFLOW in a 32-bit program.
set(CMAKE_C_FLAGS_INIT -D_FILE_OFFSET_BITS=64)
