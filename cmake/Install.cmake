# `cmake --install` puts the public headers, the static libraries (the shaders are compiled
# into them as SPIR-V arrays) and a package config into the prefix, so that a host writes
#   find_package(raybudget REQUIRED)
#   target_link_libraries(app PRIVATE raybudget::core)    # or raybudget::engine: the standalone renderer
# The libraries' private dependencies (tinygltf, Embree, OpenEXR) are link-only and found
# again by the config (static libraries carry no dependencies of their own).
include(CMakePackageConfigHelpers)

install(TARGETS raybudget_scene raybudget_bvh raybudget_select raybudget_core raybudget_io raybudget_engine raybudget_shaders
        EXPORT raybudgetTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/raybudget DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set_target_properties(raybudget_scene PROPERTIES EXPORT_NAME scene)
set_target_properties(raybudget_bvh PROPERTIES EXPORT_NAME bvh)
set_target_properties(raybudget_select PROPERTIES EXPORT_NAME select)
set_target_properties(raybudget_core PROPERTIES EXPORT_NAME core)
set_target_properties(raybudget_io PROPERTIES EXPORT_NAME io)
set_target_properties(raybudget_engine PROPERTIES EXPORT_NAME engine)
set_target_properties(raybudget_shaders PROPERTIES EXPORT_NAME shaders)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/raybudget)
install(EXPORT raybudgetTargets NAMESPACE raybudget:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/raybudgetConfig.cmake.in ${PROJECT_BINARY_DIR}/raybudgetConfig.cmake
                              INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/raybudgetConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/raybudgetConfig.cmake ${PROJECT_BINARY_DIR}/raybudgetConfigVersion.cmake DESTINATION ${config_dir})
