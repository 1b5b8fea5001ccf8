# Installs the CMake package another project finds with find_package(encore) and links as
# encore::encore: the static libraries of encore::encore, the API headers (include/encore, and
# nothing of src/: scripts/api-headers.py keeps internal headers out of it) and the package
# files. The command line (bin/encore) and the Python module (python/CMakeLists.txt) install
# beside it. tests/package builds and runs a consumer against an installed copy.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
# The libraries encore::encore links, and only those: encore_view (the window of `encore view`,
# on GLFW) serves the command line alone and has no API headers.
get_target_property(encore_libraries encore_all INTERFACE_LINK_LIBRARIES)
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
