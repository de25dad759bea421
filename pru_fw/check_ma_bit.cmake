# MA_BIT: the R30 bit that drives MA. R30 bit 0 and R31 bit 0 share one pad
# (mcasp0_aclkx: P9_31 on the BeagleBone Black, P1_36 on the PocketBeagle,
# pr0_pru0 gpi/gpo 0 on the AM437x), and R31 bit 0 is SL, the only input
# the 28-bit shift mode samples (docs/pru-facts.md §4.4): MA cannot be there.
#   biss_check_ma_bit(<bit>)      (or cmake -DMA_BIT=<bit> -P check_ma_bit.cmake)
function(biss_check_ma_bit bit)
  if(NOT bit MATCHES "^[0-9]+$" OR bit GREATER 7)
    message(FATAL_ERROR "MA_BIT '${bit}': expected an R30 bit 1..7")
  endif()
  if(bit EQUAL 0)
    message(FATAL_ERROR "MA_BIT 0: R30 bit 0 shares its pad with R31 bit 0, the SL input of "
                        "the 28-bit shift mode (P9_31 on the BeagleBone Black); pick 1..7")
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND DEFINED MA_BIT)
  biss_check_ma_bit("${MA_BIT}")
  message(STATUS "MA_BIT ${MA_BIT}: allowed")
endif()
