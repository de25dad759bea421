# biss_check_test(NAME <name> SOURCES <files...> LIBS <libs...>)
# Builds a Check test executable and registers it with CTest.
function(biss_check_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} PkgConfig::CHECK)
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR}/test/common)
  add_test(NAME ${T_NAME} COMMAND ${T_NAME})
  # Check forks per test by default; keep that (a crash fails one test, not the suite).
  set_tests_properties(${T_NAME} PROPERTIES
    ENVIRONMENT "CK_DEFAULT_TIMEOUT=60;TEST_SRC_DIR=${PROJECT_SOURCE_DIR};TEST_BIN_DIR=${PROJECT_BINARY_DIR}")
endfunction()
