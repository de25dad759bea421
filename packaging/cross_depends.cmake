# cross_depends.cmake - a cross build's CPACK_PROJECT_CONFIG_FILE (through
# the deb_depends.cmake packaging/CMakeLists.txt writes, which sets the
# deb_* variables): the packages' run-time dependencies, found as CPack's
# own shlibdeps finds them on a native build, by dpkg-shlibdeps, here told
# where the cross C library that linked the files lies (-l). Its answer
# names the cross library's package as its shlibs file does
# (libc6:armhf (>= 2.36)); on the board that is the native libc6.
file(MAKE_DIRECTORY ${deb_work}/debian)
file(WRITE ${deb_work}/debian/control "Source: pru-biss\n\nPackage: pru-biss\nArchitecture: any\n")
foreach(C LIBBISS BISSCTL)
  execute_process(COMMAND dpkg-shlibdeps -O -l${deb_libdir} ${deb_files_${C}}
                  WORKING_DIRECTORY ${deb_work} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc OR NOT out MATCHES "shlibs:Depends=([^\n]+)")
    message(FATAL_ERROR "dpkg-shlibdeps ${deb_files_${C}}: ${err}")
  endif()
  string(REPLACE ":${deb_arch}" "" deps "${CMAKE_MATCH_1}")
  if(CPACK_DEBIAN_${C}_PACKAGE_DEPENDS)
    set(deps "${deps}, ${CPACK_DEBIAN_${C}_PACKAGE_DEPENDS}")
  endif()
  set(CPACK_DEBIAN_${C}_PACKAGE_DEPENDS "${deps}")
endforeach()
