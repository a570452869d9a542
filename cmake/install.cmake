# Install rules, the exported CMake package and the Debian package (docs/install.md).
#
#   cmake --install build --prefix P
#     P/bin/stability-scan
#     P/include/abu/...                      the public headers
#     P/lib/libabu.a                         (CMAKE_INSTALL_LIBDIR)
#     P/lib/cmake/abu/abuConfig.cmake        find_package(abu CONFIG) -> abu::abu
#     P/share/abu/plots/*.gp                 found by the binary relative to itself (io.cpp)
#     P/share/abu/scenes/*.toml              the example scenes of data/scenes
#     P/share/doc/abu/                       README.md, model.md, install.md
include(CMakePackageConfigHelpers)

set(ABU_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/abu" CACHE STRING "Where abuConfig.cmake goes")

install(TARGETS abu stability-scan EXPORT abuTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/abu DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/plots/ DESTINATION ${ABU_INSTALL_PLOTSDIR} FILES_MATCHING PATTERN "*.gp")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/abu/scenes
        FILES_MATCHING PATTERN "*.toml")
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})

# abu::abu (the library) and abu::stability-scan (the program, for add_custom_command).
install(EXPORT abuTargets NAMESPACE abu:: DESTINATION ${ABU_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/abuConfig.cmake.in ${PROJECT_BINARY_DIR}/abuConfig.cmake
                              INSTALL_DESTINATION ${ABU_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/abuConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/abuConfig.cmake ${PROJECT_BINARY_DIR}/abuConfigVersion.cmake
        DESTINATION ${ABU_INSTALL_CMAKEDIR})

# Debian package: `cpack -G DEB` in the build directory (docs/install.md).
set(CPACK_PACKAGE_NAME "abu-stability")
set(CPACK_PACKAGE_VENDOR "abu-stability")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "stability-scan (equilibria, spectra, continuation, maps, simulation of the automatic ball balancer), its gnuplot scripts, and the static library libabu.a with headers and CMake package (find_package(abu)).")
set(CPACK_PACKAGE_CONTACT "abu-stability maintainers <abu-stability@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
# The program's shared libraries (libgsl, libfmt, libtomlplusplus, ...) by dpkg-shlibdeps;
# the charts need gnuplot; linking against libabu.a needs the -dev packages of its dependencies.
find_program(ABU_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(ABU_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
else()
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "libgsl27, libfmt9, libtomlplusplus3, libarpack2, libnlopt-cxx0")
endif()
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox | gnuplot")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libeigen3-dev (>= 3.4), libgsl-dev, libfmt-dev, libtomlplusplus-dev, libarpack2-dev, libnlopt-cxx-dev, cmake (>= 3.25)")
set(CPACK_GENERATOR "DEB")
set(CPACK_SOURCE_GENERATOR "TGZ")
set(CPACK_SOURCE_IGNORE_FILES "/\\\\.git/" "/build.*/" "/out/" "__pycache__")
include(CPack)
