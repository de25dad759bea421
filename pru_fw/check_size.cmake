# The image must fit the smallest PRU IRAM it targets: 4 KB on AM437x ICSS0.
# cmake -DIMAGE=path -DLIMIT=bytes -P check_size.cmake
file(SIZE "${IMAGE}" size)
if(size GREATER LIMIT)
  message(FATAL_ERROR "${IMAGE}: ${size} bytes, more than the ${LIMIT} bytes of IRAM")
endif()
message(STATUS "${IMAGE}: ${size} of ${LIMIT} bytes of IRAM")
