# Test registration helpers: every suite, C or Python, is one or more ctest tests, so
# `ctest` runs them all and its closing line counts them.
#
#   hv_add_cmocka_test(NAME <name> SOURCES <files...> [LIBS <targets...>] [LABELS <l...>])
#   hv_add_pytest(NAME <name> PATH <tests/x/test_y.py or dir> [LABELS <l...>] [TIMEOUT s])
#
# Python tests run with the project virtualenv (HV_PYTHON, default <src>/.venv/bin/python),
# get HV_BUILD_DIR / HV_SOURCE_DIR in the environment, and import `harvest` as the venv has
# it installed (scripts/setup.sh: pip install -e host).
# A test that cannot run prints "SKIPPED: <reason>" and exits 77 (ctest reports it as
# skipped, never passed): see SKIP_RETURN_CODE below and pytest's skip, which our conftest
# turns into exit code 77 when any test of a file was skipped.

find_package(PkgConfig REQUIRED)
pkg_check_modules(CMOCKA REQUIRED IMPORTED_TARGET cmocka)

set(HV_PYTHON "${CMAKE_SOURCE_DIR}/.venv/bin/python" CACHE FILEPATH "Python with the project's packages")

function(hv_add_cmocka_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE PkgConfig::CMOCKA ${T_LIBS})
  add_test(NAME ${T_NAME} COMMAND ${T_NAME})
  set_tests_properties(${T_NAME} PROPERTIES LABELS "unit;${T_LABELS}" SKIP_RETURN_CODE 77)
endfunction()

function(hv_add_pytest)
  cmake_parse_arguments(T "" "NAME;PATH;TIMEOUT" "LABELS" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  add_test(NAME ${T_NAME}
           COMMAND ${HV_PYTHON} -m pytest -q -rs -p no:cacheprovider ${CMAKE_SOURCE_DIR}/${T_PATH}
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(${T_NAME} PROPERTIES
    LABELS "python;${T_LABELS}" TIMEOUT ${T_TIMEOUT} SKIP_RETURN_CODE 77
    ENVIRONMENT "HV_BUILD_DIR=${CMAKE_BINARY_DIR};HV_SOURCE_DIR=${CMAKE_SOURCE_DIR};PYTHONDONTWRITEBYTECODE=1")
endfunction()

# A suite that an option or a missing piece leaves out is still registered: as a test that
# prints "SKIPPED: <reason>" and exits 77, so ctest lists it as skipped, never silently
# absent (and scripts/test.sh fails on it unless .ci/may_skip lists it).
function(hv_add_skipped_test NAME REASON)
  add_test(NAME ${NAME} COMMAND sh -c "echo \"SKIPPED: \$0\"; exit 77" "${REASON}")
  set_tests_properties(${NAME} PROPERTIES SKIP_RETURN_CODE 77 LABELS "skipped")
endfunction()
