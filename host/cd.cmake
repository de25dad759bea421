# Control communication codec (CDM programs and their answers). Stands
# alone: no dependency on libbiss, only the shared-memory header.
add_library(biss_cd STATIC
  ${CMAKE_CURRENT_LIST_DIR}/biss_cd_crc.c ${CMAKE_CURRENT_LIST_DIR}/biss_cd_build.c
  ${CMAKE_CURRENT_LIST_DIR}/biss_cd_parse.c ${CMAKE_CURRENT_LIST_DIR}/biss_cd_shm.c)
target_include_directories(biss_cd PUBLIC ${CMAKE_CURRENT_LIST_DIR} ${PROJECT_SOURCE_DIR}/include)
