# FindGLPK: the GNU Linear Programming Kit as the imported target GLPK::GLPK.
include(${CMAKE_CURRENT_LIST_DIR}/HvImportedLibrary.cmake)
hv_find_imported_library(GLPK HEADER glpk.h LIBRARY glpk TARGET GLPK::GLPK)
