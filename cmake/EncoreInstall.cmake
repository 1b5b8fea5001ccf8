# Installs the libraries, headers and a CMake package so another project can
#   find_package(encore) and link encore::encore.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
get_property(encore_libraries GLOBAL PROPERTY ENCORE_LIBRARIES)
install(TARGETS ${encore_libraries} encore_all EXPORT encoreTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS encore RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/encore DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT encoreTargets NAMESPACE encore:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/encore)
configure_package_config_file(cmake/encoreConfig.cmake.in
    ${CMAKE_CURRENT_BINARY_DIR}/encoreConfig.cmake
    INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/encore)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/encoreConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/encoreConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/encoreConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/encore)
