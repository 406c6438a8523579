# cmake -D TEST_EXECUTABLE=exe -D TEST_NAME=name -D OUTPUT=file -P BoostTestDiscover.cmake
# Writes one add_test() per enabled Boost.Test case of `exe` into `file`, named
# name.suite/case, run as `exe --run_test=suite/case`. `--list_content` prints the tree
# with four spaces of indentation per level and '*' after every enabled unit; a unit
# followed by a deeper line is a suite, any other is a test case.
include(${CMAKE_CURRENT_LIST_DIR}/BoostTestList.cmake)
modalbench_boost_cases("${TEST_EXECUTABLE}" cases)
set(content "")
foreach(path IN LISTS cases)
  string(APPEND content
    "add_test([=[${TEST_NAME}.${path}]=] [==[${TEST_EXECUTABLE}]==] [=[--run_test=${path}]=] --log_level=message)\n")
endforeach()
file(WRITE ${OUTPUT} "${content}")
