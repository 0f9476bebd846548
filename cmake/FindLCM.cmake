# FindLCM: LCM's C library as the imported target LCM::lcm, linked statically (liblcm.a),
# so that programs carry LCM and need only glib's shared library at run time.
# Give the prefix with LCM_ROOT (CMake's <Pkg>_ROOT): a prefix with include/lcm/ and
# lib/liblcm.a, such as the site-packages of a Python environment with pip's `lcm` wheel,
# which holds both. Header and library are taken from one prefix, and the version from
# its lcm_version.h (LCM_VERSION), so find_package(LCM 1.5.3 EXACT) refuses any other.
include(FindPackageHandleStandardArgs)
find_path(LCM_INCLUDE_DIR NAMES lcm/lcm.h)
set(LCM_VERSION "unknown")
if(LCM_INCLUDE_DIR)
  get_filename_component(_lcm_prefix "${LCM_INCLUDE_DIR}" DIRECTORY)
  find_library(LCM_LIBRARY NAMES liblcm.a NO_DEFAULT_PATH
               PATHS "${_lcm_prefix}/lib" "${_lcm_prefix}/lib/${CMAKE_LIBRARY_ARCHITECTURE}")
  if(EXISTS "${LCM_INCLUDE_DIR}/lcm/lcm_version.h") # LCM before 1.4 has none
    file(STRINGS "${LCM_INCLUDE_DIR}/lcm/lcm_version.h" _lcm_v
         REGEX "^#define LCM_VERSION_(MAJOR|MINOR|PATCH) +[0-9]+")
    string(REGEX REPLACE ".*MAJOR +([0-9]+).*MINOR +([0-9]+).*PATCH +([0-9]+).*"
           "\\1.\\2.\\3" LCM_VERSION "${_lcm_v}")
  endif()
endif()
mark_as_advanced(LCM_INCLUDE_DIR LCM_LIBRARY)
find_package_handle_standard_args(LCM REQUIRED_VARS LCM_LIBRARY LCM_INCLUDE_DIR
                                  VERSION_VAR LCM_VERSION)
if(LCM_FOUND)
  # liblcm.a's own dependencies: glib (pkg-config glib-2.0) and threads
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(LCM_GLIB QUIET IMPORTED_TARGET glib-2.0)
  endif()
  find_package(Threads)
  if(NOT TARGET PkgConfig::LCM_GLIB OR NOT Threads_FOUND)
    set(LCM_FOUND FALSE)
    if(LCM_FIND_REQUIRED)
      message(FATAL_ERROR "LCM's static library needs glib's development files (pkg-config "
                          "glib-2.0; Debian: libglib2.0-dev) and threads")
    endif()
  endif()
endif()
if(LCM_FOUND AND NOT TARGET LCM::lcm)
  add_library(LCM::lcm STATIC IMPORTED)
  set_target_properties(LCM::lcm PROPERTIES IMPORTED_LOCATION "${LCM_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LCM_INCLUDE_DIR}" INTERFACE_COMPILE_DEFINITIONS LCM_STATIC
    INTERFACE_LINK_LIBRARIES "PkgConfig::LCM_GLIB;Threads::Threads")
endif()
