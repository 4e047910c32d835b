# `cmake --install build [--prefix P]` and `cpack -G DEB`. One install component per package,
# shaped by what users install (docs/packaging.md):
#   aosuite          (tool)   bin/aosuite and the image path's plugins: compare, check, bless,
#                             report on PNG, EXR, JPEG, TIFF, WebP, HDR, Targa, BMP
#   aosuite-oiio     (oiio)   the OpenImageIO fallback for every other format (Suggests)
#   aosuite-ao       (ao)     the AO bench: renderer, reference, studies (GL, Embree, assimp, OpenCV)
#   libaosuite-dev   (dev)    libaosuite.so, its headers and the CMake package (find_package)
#   python3-aosuite  (python) `import aosuite` and the pytest plugin (python/CMakeLists.txt)
# Plugins go in AOSUITE_PLUGIN_DIR (lib/<multiarch>/aosuite), where sibling_library.hpp looks.
# Everything else aosuite reads at run time (shaders, report pages) is built into it.
include(CMakePackageConfigHelpers)

install(TARGETS aosuite RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tool)
install(TARGETS aosuite_check aosuite_exr aosuite_codecs
        LIBRARY DESTINATION ${AOSUITE_PLUGIN_DIR} COMPONENT tool)
install(TARGETS aosuite_oiio LIBRARY DESTINATION ${AOSUITE_PLUGIN_DIR} COMPONENT oiio)
if(AOSUITE_RENDERER)
  install(TARGETS aosuite_gl LIBRARY DESTINATION ${AOSUITE_PLUGIN_DIR} COMPONENT ao)
endif()

install(TARGETS aosuite_api EXPORT aosuiteTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_SOURCE_DIR}/include/aosuite/aosuite.hpp
              ${PROJECT_SOURCE_DIR}/include/aosuite/gtest.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aosuite COMPONENT dev)
install(EXPORT aosuiteTargets NAMESPACE aosuite::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aosuite COMPONENT dev)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/aosuiteConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
file(WRITE ${PROJECT_BINARY_DIR}/aosuiteConfig.cmake
     "include(\${CMAKE_CURRENT_LIST_DIR}/aosuiteTargets.cmake)\n")
install(FILES ${PROJECT_BINARY_DIR}/aosuiteConfig.cmake
              ${PROJECT_BINARY_DIR}/aosuiteConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aosuite COMPONENT dev)

# The Debian packages. Each one's Depends are the packages of the libraries its files link
# (dpkg-shlibdeps), plus what is opened at run time: the Mesa drivers EGL loads, NumPy.
set(AOSUITE_PACKAGES tool oiio dev)
if(AOSUITE_RENDERER)
  list(APPEND AOSUITE_PACKAGES ao)
endif()
if(AOSUITE_PYTHON)
  list(APPEND AOSUITE_PACKAGES python)
endif()
set(AOSUITE_MAINTAINER "aosuite maintainers <maintainers@users.noreply.h-seed-14f15255.example>"
    CACHE STRING "The packages' Maintainer field")
set(package_tool aosuite)
set(package_oiio aosuite-oiio)
set(package_ao aosuite-ao)
set(package_dev libaosuite-dev)
set(package_python python3-aosuite)
execute_process(COMMAND gzip -9nc ${PROJECT_SOURCE_DIR}/cmake/debian/changelog
                OUTPUT_FILE ${PROJECT_BINARY_DIR}/changelog.gz COMMAND_ERROR_IS_FATAL ANY)
foreach(component ${AOSUITE_PACKAGES})
  string(TOUPPER ${component} C)
  set(CPACK_DEBIAN_${C}_PACKAGE_NAME ${package_${component}})
  # Its summary line, then the long description (no semicolons: CMake lists).
  file(READ ${PROJECT_SOURCE_DIR}/cmake/debian/${package_${component}}.description description)
  string(STRIP "${description}" CPACK_COMPONENT_${C}_DESCRIPTION)
  # Debian policy 12.5 and 12.7: every package carries the copyright file and its changelog
  # (gzip -9n) in /usr/share/doc/<package>.
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/debian/copyright ${PROJECT_BINARY_DIR}/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/${package_${component}}
          COMPONENT ${component})
endforeach()
set(CPACK_COMPONENTS_ALL ${AOSUITE_PACKAGES})
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)  # CPACK_COMPONENT_<C>_DEPENDS: "aosuite (= 0.1.0)"
set(CPACK_PACKAGE_NAME aosuite)
set(CPACK_PACKAGE_VENDOR "aosuite project")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${AOSUITE_MAINTAINER}")
set(CPACK_PACKAGE_HOMEPAGE_URL "https://github.com/aosuite/aosuite")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libaosuite.so.0's shlibs file and ldconfig trigger (libaosuite-dev); stripped binaries.
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)

set(CPACK_DEBIAN_TOOL_PACKAGE_SUGGESTS "aosuite-oiio, aosuite-ao, python3-aosuite")
set(CPACK_DEBIAN_TOOL_PACKAGE_SECTION graphics)

set(CPACK_COMPONENT_OIIO_DEPENDS tool)
set(CPACK_DEBIAN_OIIO_PACKAGE_SECTION graphics)

set(CPACK_COMPONENT_AO_DEPENDS tool)
set(CPACK_DEBIAN_AO_PACKAGE_DEPENDS "libgl1-mesa-dri")
set(CPACK_DEBIAN_AO_PACKAGE_SECTION graphics)

set(CPACK_COMPONENT_DEV_DEPENDS tool)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/cmake/debian/triggers)

set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "python3, python3-numpy")
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
include(CPack)
