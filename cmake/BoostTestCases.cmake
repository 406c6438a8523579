# modalbench_add_boost_test(NAME name SOURCES a.cpp ... LIBS ...)
# Builds one Boost.Test executable and registers every test case in CTest on its own
# (suite/case), so CTest's counts are real. The cases are discovered after each build from
# the executable's own `--list_content` (never by reading the sources), so every case Boost
# knows is a CTest test. `test_registration_complete` (tests/CMakeLists.txt) checks it.
set(MODALBENCH_BOOST_DISCOVER_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/BoostTestDiscover.cmake)

function(modalbench_add_boost_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} Boost::unit_test_framework modalbench_warnings)
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR}/tests/common)
  target_compile_definitions(${T_NAME} PRIVATE BOOST_TEST_DYN_LINK
    MODALBENCH_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes"
    MODALBENCH_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
  set(cases_file ${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_cases.cmake)
  set(include_file ${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_include.cmake)
  add_custom_command(TARGET ${T_NAME} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -D TEST_EXECUTABLE=$<TARGET_FILE:${T_NAME}> -D TEST_NAME=${T_NAME}
            -D OUTPUT=${cases_file} -P ${MODALBENCH_BOOST_DISCOVER_SCRIPT}
    BYPRODUCTS ${cases_file}
    COMMENT "Listing the test cases of ${T_NAME}"
    VERBATIM)
  file(WRITE ${include_file}
    "if(EXISTS \"${cases_file}\")\n"
    "  include(\"${cases_file}\")\n"
    "else()\n"
    "  add_test(${T_NAME}_NOT_BUILT ${T_NAME}_NOT_BUILT)\n"
    "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${include_file})
  set_property(GLOBAL APPEND PROPERTY MODALBENCH_BOOST_TESTS ${T_NAME})
endfunction()
