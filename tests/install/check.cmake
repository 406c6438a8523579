# cmake -D BUILD_DIR=... -D SOURCE_DIR=... -D WORK=... -D GENERATOR=... -P check.cmake
# Installs the build into WORK/prefix, then configures, builds and runs tests/install/consumer
# against it with find_package(modalbench CONFIG REQUIRED).
file(REMOVE_RECURSE ${WORK})
foreach(step
    "${CMAKE_COMMAND};--install;${BUILD_DIR};--prefix;${WORK}/prefix"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/tests/install/consumer;-B;${WORK}/build;-G;${GENERATOR};-DCMAKE_BUILD_TYPE=Release;-DCMAKE_PREFIX_PATH=${WORK}/prefix"
    "${CMAKE_COMMAND};--build;${WORK}/build"
    "${WORK}/build/consumer;${SOURCE_DIR}/scenes/paper_fixed_beam.toml")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${err}")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
