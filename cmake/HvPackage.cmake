# The Debian package: `cpack -G DEB` in a build folder makes harvest_VERSION_ARCH.deb from
# the install tree under /usr, plus what only a vehicle computer wants (packaging/): the
# config and the services' settings in /etc/harvest (conffiles), the systemd units, the CAN
# bring-up, and the maintainer scripts that make the `harvest` system user.
#
# Those extras are the install component `vehicle`, left out of a plain `cmake --install`
# (EXCLUDE_FROM_ALL): an install into any prefix stays a tree that writes nothing outside
# itself, and only the package puts files in /etc and the systemd folder.

set(HV_SYSTEMD_UNIT_DIR /lib/systemd/system CACHE PATH
    "Where the package puts its systemd units (Debian 12: /lib/systemd/system)")
set(HV_PACKAGE_PREFIX /usr) # the package's install prefix; the units name programs under it

if(TARGET harvest-exec)
  # The bus bit rate is the protocol's: the DBC's network attribute Baudrate (bit/s).
  set(_hv_dbc ${CMAKE_SOURCE_DIR}/executor/can/harvest.dbc)
  file(STRINGS ${_hv_dbc} _hv_baud REGEX "^BA_ \"Baudrate\" [0-9]+;")
  if(NOT _hv_baud MATCHES "^BA_ \"Baudrate\" ([0-9]+)")
    message(FATAL_ERROR "${_hv_dbc}: network attribute Baudrate: missing or not one "
                        "BA_ \"Baudrate\" N; line (the CAN bit rate the package sets)")
  endif()
  set(HV_CAN_BITRATE ${CMAKE_MATCH_1})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_hv_dbc})

  set(HV_BINDIR ${HV_PACKAGE_PREFIX}/${CMAKE_INSTALL_BINDIR})
  set(HV_LIBEXEC ${HV_PACKAGE_PREFIX}/${CMAKE_INSTALL_LIBEXECDIR}/harvest)
  set(_hv_units harvest-can.service harvest-exec.service harvest-plan-online.service)
  set(_hv_unit_files)
  foreach(unit ${_hv_units})
    configure_file(packaging/systemd/${unit}.in ${CMAKE_BINARY_DIR}/packaging/${unit} @ONLY)
    list(APPEND _hv_unit_files ${CMAKE_BINARY_DIR}/packaging/${unit})
  endforeach()
  install(FILES ${_hv_unit_files} DESTINATION ${HV_SYSTEMD_UNIT_DIR}
          COMPONENT vehicle EXCLUDE_FROM_ALL)
  install(PROGRAMS packaging/harvest-can-up DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/harvest
          COMPONENT vehicle EXCLUDE_FROM_ALL)
  # the conffiles: an operator's edits survive upgrades (dpkg asks before replacing them)
  install(FILES config/harvest.cfg packaging/harvest.env DESTINATION /etc/harvest
          COMPONENT vehicle EXCLUDE_FROM_ALL)
  install(FILES docs/INSTALL.md docs/EXIT_CODES.md DESTINATION ${CMAKE_INSTALL_DOCDIR}
          COMPONENT vehicle EXCLUDE_FROM_ALL)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME harvest)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION}) # the file VERSION, through project()
set(CPACK_PACKAGE_CONTACT "harvest maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "dual-arm strawberry-harvesting robot: planner, executor, CAN tools")
set(CPACK_PACKAGE_DESCRIPTION
    "The planner (offline MILP and online), the executor on SocketCAN with its systemd \
units, the CAN tools, the static libraries and headers, the protocol's DBC and the \
default configuration.")
set(CPACK_PACKAGING_INSTALL_PREFIX ${HV_PACKAGE_PREFIX})
# One package of both components, the tree of `cmake --install` (Unspecified) and
# `vehicle`: a component install, or CPack would leave out what EXCLUDE_FROM_ALL marks.
set(CPACK_COMPONENTS_ALL Unspecified vehicle)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON) # glib, jansson, GLPK... from the programs' needs
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser, iproute2")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${CMAKE_SOURCE_DIR}/packaging/debian/postinst ${CMAKE_SOURCE_DIR}/packaging/debian/prerm
    ${CMAKE_SOURCE_DIR}/packaging/debian/postrm ${CMAKE_SOURCE_DIR}/packaging/debian/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
