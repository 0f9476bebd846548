# FindLCM: the LCM C library as the imported target LCM::lcm (lcm-gen is found apart).
include(${CMAKE_CURRENT_LIST_DIR}/HvImportedLibrary.cmake)
hv_find_imported_library(LCM HEADER lcm/lcm.h LIBRARY lcm TARGET LCM::lcm)
