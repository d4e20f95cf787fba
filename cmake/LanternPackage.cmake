# The installed package (docs/extending.md): `cmake --install build --prefix P` puts the
# engine libraries, their public headers, the engine's shader libraries, the GLSL includes
# and LanternConfig.cmake under P, so that a project of its own writes
#
#   find_package(Lantern 0.1 REQUIRED)
#   target_link_libraries(my_tool PRIVATE Lantern::systems)
#
# and gets Lantern's headers, C++20 and its dependencies (found again by the config), but
# none of Lantern's build flags (warnings, -Werror, sanitizers stay PRIVATE).
include_guard(GLOBAL)
include(CMakePackageConfigHelpers)

set(LANTERN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Lantern)
install(EXPORT LanternTargets NAMESPACE Lantern:: DESTINATION ${LANTERN_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/LanternConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/LanternConfig.cmake
                              INSTALL_DESTINATION ${LANTERN_CMAKE_DIR}
                              PATH_VARS CMAKE_INSTALL_DATADIR)
# 0.x: a minor version may break the API (docs/extending.md, "Versions").
write_basic_package_version_file(${CMAKE_BINARY_DIR}/LanternConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/LanternConfig.cmake ${CMAKE_BINARY_DIR}/LanternConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/LanternShaders.cmake
        DESTINATION ${LANTERN_CMAKE_DIR})
