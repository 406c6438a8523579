# `cmake --install`: headers, the libraries, the `modalbench` executable and a package config, so
# that another project's find_package(modalbench CONFIG REQUIRED) gives modalbench::core,
# modalbench::numerics, modalbench::exact, modalbench::rfem, modalbench::rom, ... (the static libraries
# with everything they link).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(modalbench_install_targets modalbench_numerics modalbench_core modalbench_exact modalbench_solvers modalbench_rom
    modalbench_harness modalbench_warnings)
foreach(backend IN LISTS MODALBENCH_BACKENDS)
  if(TARGET modalbench_${backend})
    list(APPEND modalbench_install_targets modalbench_${backend})
  endif()
endforeach()
if(TARGET modalbench_cholmod)
  list(APPEND modalbench_install_targets modalbench_cholmod)
endif()
foreach(t IN LISTS modalbench_install_targets)
  string(REPLACE "modalbench_" "" short ${t})
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${short})
endforeach()

install(TARGETS ${modalbench_install_targets} EXPORT modalbenchTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS modalbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir numerics core exact solvers rom harness ${MODALBENCH_BACKENDS})
  if(EXISTS ${PROJECT_SOURCE_DIR}/${dir}/include)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endforeach()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/modalbench)
install(EXPORT modalbenchTargets NAMESPACE modalbench:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/modalbenchConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/modalbenchConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/modalbenchConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/modalbenchConfig.cmake ${PROJECT_BINARY_DIR}/modalbenchConfigVersion.cmake
        DESTINATION ${config_dir})
