# Installs every library made with wbi_add_library (and wbi::idl) as one CMake
# package, so that a user's project can find_package(wbi) and link wbi::proxy.
include(CMakePackageConfigHelpers)

get_property(wbi_targets GLOBAL PROPERTY WBI_INSTALLED_TARGETS)
install(TARGETS ${wbi_targets} EXPORT wbiTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT wbiTargets NAMESPACE wbi:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/wbi)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/wbiConfig.cmake.in
  ${PROJECT_BINARY_DIR}/wbiConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/wbi)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/wbiConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/wbiConfig.cmake ${PROJECT_BINARY_DIR}/wbiConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/WbiPlugin.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/wbi)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/deploy/ DESTINATION ${CMAKE_INSTALL_DATADIR}/wbi/deploy
  FILES_MATCHING PATTERN "*.yaml" PATTERN "*.xml")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/models/ DESTINATION ${CMAKE_INSTALL_DATADIR}/wbi/models
  FILES_MATCHING PATTERN "*.urdf")
