# The packages demlight's libraries (src, geo, lighting, products) link: found by the build
# (CMakeLists.txt) and again by a consumer's find_package(demlight) (demlightConfig.cmake.in),
# which defines demlight_find_package as find_dependency first. The libraries are static, so a
# consumer links their private dependencies too.
if(NOT COMMAND demlight_find_package)
  macro(demlight_find_package)
    find_package(${ARGV} REQUIRED)
  endmacro()
endif()

list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
demlight_find_package(GDAL CONFIG)
demlight_find_package(GeographicLib)
demlight_find_package(glm CONFIG)
demlight_find_package(date CONFIG)
demlight_find_package(TBB CONFIG)
# libtiff and zstd (libtiff-dev, libzstd-dev): Float32 GeoTIFF tiles encoded by demlight
# (geo/tiff_tiles.cpp), in the file GDAL creates with the same libtiff.
demlight_find_package(TIFF)
demlight_find_package(zstd CONFIG)
# libdeflate (libdeflate-dev): PNG previews (geo/png_writer.cpp); Debian 12 ships no CMake config.
demlight_find_package(PkgConfig)
pkg_check_modules(libdeflate REQUIRED IMPORTED_TARGET libdeflate)

if(NOT TARGET GeographicLib::GeographicLib)
  add_library(GeographicLib::GeographicLib INTERFACE IMPORTED)
  target_include_directories(GeographicLib::GeographicLib INTERFACE ${GeographicLib_INCLUDE_DIRS})
  target_link_libraries(GeographicLib::GeographicLib INTERFACE ${GeographicLib_LIBRARIES})
endif()
