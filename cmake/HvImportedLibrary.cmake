# hv_find_imported_library(<Pkg> HEADER <h> LIBRARY <name> TARGET <ns::name>)
# The body of our Find<Pkg>.cmake modules for C libraries that Debian ships without a
# usable CMake package or .pc file (GLPK has none). Sets <Pkg>_FOUND, <Pkg>_INCLUDE_DIR,
# <Pkg>_LIBRARY and defines the imported target, so that exported harvest:: targets name
# the target, never the build machine's absolute library path.
include(FindPackageHandleStandardArgs)
function(hv_find_imported_library pkg)
  cmake_parse_arguments(A "" "HEADER;LIBRARY;TARGET" "" ${ARGN})
  find_path(${pkg}_INCLUDE_DIR NAMES ${A_HEADER})
  find_library(${pkg}_LIBRARY NAMES ${A_LIBRARY})
  mark_as_advanced(${pkg}_INCLUDE_DIR ${pkg}_LIBRARY)
  find_package_handle_standard_args(${pkg} REQUIRED_VARS ${pkg}_LIBRARY ${pkg}_INCLUDE_DIR)
  set(${pkg}_FOUND ${${pkg}_FOUND} PARENT_SCOPE)
  if(${pkg}_FOUND AND NOT TARGET ${A_TARGET})
    add_library(${A_TARGET} UNKNOWN IMPORTED)
    set_target_properties(${A_TARGET} PROPERTIES IMPORTED_LOCATION "${${pkg}_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${${pkg}_INCLUDE_DIR}")
  endif()
endfunction()
