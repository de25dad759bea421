# cpack_project.cmake - CPack's project configuration file (through the one
# packaging/CMakeLists.txt writes, which sets the deb_* variables), run by
# cpack before it packages.
#
# Conffiles: every file a package installs under /etc is a conffile
# (Debian policy 10.7.2: dpkg keeps the administrator's changes). Each
# packaged component is installed into a scratch tree to see which.
file(REMOVE_RECURSE ${deb_work})
foreach(component IN LISTS CPACK_COMPONENTS_ALL)
  set(tree ${deb_work}/${component}/tree)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env DESTDIR=${tree}
                          ${CMAKE_COMMAND} --install ${deb_build} --component ${component}
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "installing ${component} to find its conffiles: ${err}")
  endif()
  file(GLOB_RECURSE etc LIST_DIRECTORIES false RELATIVE ${tree} ${tree}/etc/*)
  if(etc)
    list(SORT etc)
    list(TRANSFORM etc PREPEND /)
    list(JOIN etc "\n" lines)
    file(WRITE ${deb_work}/${component}/conffiles "${lines}\n")
    string(TOUPPER ${component} C)
    list(APPEND CPACK_DEBIAN_${C}_PACKAGE_CONTROL_EXTRA ${deb_work}/${component}/conffiles)
  endif()
endforeach()

# A cross build's run-time dependencies, found as CPack's shlibdeps finds
# a native build's: dpkg-shlibdeps, here told where the cross C library
# that linked the files lies (-l). Its answer names the cross library's
# package as its shlibs file does (libc6:armhf (>= 2.36)); on the board
# that is the native libc6.
if(deb_cross)
  file(MAKE_DIRECTORY ${deb_work}/shlibdeps/debian)
  file(WRITE ${deb_work}/shlibdeps/debian/control
       "Source: pru-biss\n\nPackage: pru-biss\nArchitecture: any\n")
  foreach(C LIBBISS BISSCTL)
    execute_process(COMMAND dpkg-shlibdeps -O -l${deb_libdir} ${deb_files_${C}}
                    WORKING_DIRECTORY ${deb_work}/shlibdeps RESULT_VARIABLE rc
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
endif()
