# hv_install_pkgconfig(NAME <file stem> DESCRIPTION <text> LIBS <-l...> [REQUIRES <pkgs>])
# writes <build>/<NAME>.pc and installs it in <libdir>/pkgconfig. The prefix is found from
# the .pc file's own place (${pcfiledir}), so an installed tree can be moved or installed
# with `cmake --install --prefix P` into any P without editing it.
function(hv_install_pkgconfig)
  cmake_parse_arguments(P "" "NAME;DESCRIPTION" "LIBS;REQUIRES" ${ARGN})
  file(RELATIVE_PATH up "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
  string(REGEX REPLACE "/$" "" up "${up}")
  list(JOIN P_LIBS " " libs)
  list(JOIN P_REQUIRES " " requires)
  set(text "prefix=\${pcfiledir}/${up}\nlibdir=\${prefix}/${CMAKE_INSTALL_LIBDIR}\n")
  string(APPEND text "includedir=\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}\n\n")
  string(APPEND text "Name: ${P_NAME}\nDescription: ${P_DESCRIPTION}\n")
  string(APPEND text "Version: ${PROJECT_VERSION}\n")
  if(requires)
    string(APPEND text "Requires: ${requires}\n")
  endif()
  # Static libraries only: their own dependencies belong in Libs, not Libs.private.
  string(APPEND text "Libs: -L\${libdir} ${libs}\nCflags: -I\${includedir}\n")
  file(GENERATE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${P_NAME}.pc CONTENT "${text}")
  install(FILES ${CMAKE_CURRENT_BINARY_DIR}/${P_NAME}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
