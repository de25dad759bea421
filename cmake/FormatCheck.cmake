# A test that every C source and header is as clang-format (.clang-format)
# lays it out. scripts/setup.sh installs clang-format; without it the test
# is not defined (and CMake says so).
find_program(CLANG_FORMAT clang-format)
if(CLANG_FORMAT)
  file(GLOB_RECURSE BISS_FORMAT_FILES CONFIGURE_DEPENDS
       ${PROJECT_SOURCE_DIR}/emulator/*.c ${PROJECT_SOURCE_DIR}/emulator/*.h
       ${PROJECT_SOURCE_DIR}/host/*.c ${PROJECT_SOURCE_DIR}/host/*.h
       ${PROJECT_SOURCE_DIR}/include/*.h ${PROJECT_SOURCE_DIR}/test/*.c
       ${PROJECT_SOURCE_DIR}/test/*.h ${PROJECT_SOURCE_DIR}/examples/*.c)
  # test/golden/ holds frozen copies (the firmware's header among them) that
  # must stay as they were recorded, whatever clang-format says later.
  list(FILTER BISS_FORMAT_FILES EXCLUDE REGEX "/test/golden/")
  add_test(NAME clang_format COMMAND ${CLANG_FORMAT} --dry-run -Werror ${BISS_FORMAT_FILES})
else()
  message(STATUS "clang-format not found: no formatting test (scripts/setup.sh installs it)")
endif()
