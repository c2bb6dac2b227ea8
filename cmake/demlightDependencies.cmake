# The packages demlight's libraries (src, geo, lighting, products) link: found by the build
# (CMakeLists.txt) and again by a consumer's find_package(demlight) (demlightConfig.cmake.in),
# which defines demlight_find_package as find_dependency first. The libraries are static, so a
# consumer links their private dependencies too.
if(NOT COMMAND demlight_find_package)
  macro(demlight_find_package)
    find_package(${ARGV} REQUIRED)
  endmacro()
endif()

# GeographicLib installs its find module (FindGeographicLib.cmake) beside its other CMake files
# rather than a config; look for it under the prefixes CMake searches.
find_path(DEMLIGHT_GEOGRAPHICLIB_MODULE_DIR FindGeographicLib.cmake
          PATH_SUFFIXES share/cmake/geographiclib lib/cmake/GeographicLib share/cmake/GeographicLib
          PATHS ${CMAKE_SYSTEM_PREFIX_PATH})
if(DEMLIGHT_GEOGRAPHICLIB_MODULE_DIR)
  list(APPEND CMAKE_MODULE_PATH ${DEMLIGHT_GEOGRAPHICLIB_MODULE_DIR})
endif()
demlight_find_package(GDAL CONFIG)
demlight_find_package(GeographicLib)
demlight_find_package(glm CONFIG)
demlight_find_package(date CONFIG)
demlight_find_package(TBB CONFIG)
# libtiff and zstd (libtiff-dev, libzstd-dev): Float32 GeoTIFF tiles encoded by demlight
# (demlight/geo/tiff_tiles.cpp), in the file GDAL creates with the same libtiff.
demlight_find_package(TIFF)
demlight_find_package(zstd CONFIG)
# libdeflate (libdeflate-dev): PNG previews (demlight/geo/png_writer.cpp); Debian 12 ships no CMake config.
demlight_find_package(PkgConfig)
pkg_check_modules(libdeflate REQUIRED IMPORTED_TARGET libdeflate)

if(NOT TARGET GeographicLib::GeographicLib)
  add_library(GeographicLib::GeographicLib INTERFACE IMPORTED)
  target_include_directories(GeographicLib::GeographicLib INTERFACE ${GeographicLib_INCLUDE_DIRS})
  target_link_libraries(GeographicLib::GeographicLib INTERFACE ${GeographicLib_LIBRARIES})
endif()
