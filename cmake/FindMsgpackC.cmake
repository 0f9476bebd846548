# FindMsgpackC: msgpack-c, MessagePack's C library (not the C++ msgpack-cxx), as the
# imported target MsgpackC::MsgpackC. Its own CMake package is `msgpack-c` from 6.0 on
# (target msgpack-c) and `msgpack` before (target msgpackc); then, for an install without
# a CMake package, pkg-config's msgpack-c.pc or msgpack.pc.
# Sets MsgpackC_FOUND, MsgpackC_VERSION, MsgpackC_PACKAGE (which package it is) and
# MsgpackC_PKG_CONFIG_NAME (the .pc file a pkg-config user of harvest names: msgpack-c
# installs one named as its CMake package).
include(FindPackageHandleStandardArgs)
set(MsgpackC_PACKAGE "")
set(_msgpackc_link "")

find_package(msgpack-c CONFIG QUIET)
if(msgpack-c_FOUND AND TARGET msgpack-c)
  set(_msgpackc_link msgpack-c)
  set(MsgpackC_VERSION ${msgpack-c_VERSION})
  set(MsgpackC_PKG_CONFIG_NAME msgpack-c)
  set(MsgpackC_PACKAGE "CMake package msgpack-c (${msgpack-c_DIR})")
else()
  # Before 6.0 msgpack-cxx's package was also called `msgpack`, in lib/cmake/msgpackc-cxx/:
  # sorted by name, ascending, lib/cmake/msgpack/ comes first, and only a package with the
  # C target counts.
  set(_msgpackc_order "${CMAKE_FIND_PACKAGE_SORT_ORDER}")
  set(_msgpackc_direction "${CMAKE_FIND_PACKAGE_SORT_DIRECTION}")
  set(CMAKE_FIND_PACKAGE_SORT_ORDER NAME)
  set(CMAKE_FIND_PACKAGE_SORT_DIRECTION ASC)
  find_package(msgpack CONFIG QUIET)
  set(CMAKE_FIND_PACKAGE_SORT_ORDER "${_msgpackc_order}")
  set(CMAKE_FIND_PACKAGE_SORT_DIRECTION "${_msgpackc_direction}")
  if(msgpack_FOUND AND TARGET msgpackc)
    set(_msgpackc_link msgpackc)
    set(MsgpackC_VERSION ${msgpack_VERSION})
    set(MsgpackC_PKG_CONFIG_NAME msgpack)
    set(MsgpackC_PACKAGE "CMake package msgpack (${msgpack_DIR})")
  endif()
endif()

if(NOT _msgpackc_link)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_search_module(MSGPACKC QUIET IMPORTED_TARGET msgpack-c msgpack)
  endif()
  if(TARGET PkgConfig::MSGPACKC)
    set(_msgpackc_link PkgConfig::MSGPACKC)
    set(MsgpackC_VERSION ${MSGPACKC_VERSION})
    set(MsgpackC_PKG_CONFIG_NAME ${MSGPACKC_MODULE_NAME})
    set(MsgpackC_PACKAGE "pkg-config ${MSGPACKC_MODULE_NAME}")
  endif()
endif()

find_package_handle_standard_args(MsgpackC REQUIRED_VARS MsgpackC_PACKAGE
  VERSION_VAR MsgpackC_VERSION
  REASON_FAILURE_MESSAGE "no CMake package msgpack-c or msgpack with the C library's target, \
no pkg-config msgpack-c or msgpack (Debian: libmsgpack-dev)")
if(MsgpackC_FOUND AND NOT TARGET MsgpackC::MsgpackC)
  add_library(MsgpackC::MsgpackC INTERFACE IMPORTED)
  set_target_properties(MsgpackC::MsgpackC PROPERTIES INTERFACE_LINK_LIBRARIES ${_msgpackc_link})
endif()
unset(_msgpackc_order)
unset(_msgpackc_direction)
unset(_msgpackc_link)
