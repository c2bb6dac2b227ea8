# cmake --install: the CLI (bin/demlight with the picture plugin it loads from its own folder),
# and the C++ package: the static libraries, their headers under include/demlight/<folder>/ (a
# consumer, like the sources, writes #include <demlight/geo/dem_source.h>) and a config for
# find_package(demlight) that provides demlight::demlight (docs/cpp.md). These are the project's
# only install rules.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(DEMLIGHT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/demlight)

# The libraries' one entry point for consumers: the runner, the products and everything they
# use. (The target `demlight` is the CLI, so this one is exported under that name.)
add_library(demlight_library INTERFACE)
set_target_properties(demlight_library PROPERTIES EXPORT_NAME demlight)
add_library(demlight::demlight ALIAS demlight_library)
target_link_libraries(demlight_library INTERFACE demlight_run)

# Only the libraries are exported (the warning flags are the build's own: $<BUILD_INTERFACE>).
install(TARGETS demlight_library demlight_run demlight_products demlight_lighting demlight_geo demlight_core
        EXPORT demlightTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

install(EXPORT demlightTargets NAMESPACE demlight:: DESTINATION ${DEMLIGHT_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/demlightConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/demlightConfig.cmake
                              INSTALL_DESTINATION ${DEMLIGHT_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/demlightConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/demlightConfig.cmake ${PROJECT_BINARY_DIR}/demlightConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/demlightDependencies.cmake
        DESTINATION ${DEMLIGHT_INSTALL_CMAKEDIR})

# The launcher, the program it runs and the program's picture plugin, in one folder: each finds
# the next in its own folder.
install(TARGETS demlight demlight_core_program RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS demlight_oiio LIBRARY DESTINATION ${CMAKE_INSTALL_BINDIR})
