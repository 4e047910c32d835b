# `cmake --install build [--prefix P]` and `cpack -G DEB`: P/bin/aosuite, the libraries it opens
# on demand in P/lib/aosuite (sibling_library.hpp finds them there), and the C++ package:
# P/lib/libaosuite.so with P/include/aosuite/aosuite.hpp, found by find_package(aosuite).
# Everything else aosuite reads at run time (shaders, report pages) is built into it.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS aosuite RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
set(AOSUITE_PLUGINS aosuite_check aosuite_exr aosuite_codecs aosuite_oiio)
if(AOSUITE_RENDERER)
  list(APPEND AOSUITE_PLUGINS aosuite_gl)
endif()
install(TARGETS ${AOSUITE_PLUGINS} LIBRARY DESTINATION lib/aosuite)

install(TARGETS aosuite_api EXPORT aosuiteTargets
        LIBRARY DESTINATION lib
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_SOURCE_DIR}/include/aosuite/aosuite.hpp
              ${PROJECT_SOURCE_DIR}/include/aosuite/gtest.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aosuite)
install(EXPORT aosuiteTargets NAMESPACE aosuite:: DESTINATION lib/cmake/aosuite)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/aosuiteConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
file(WRITE ${PROJECT_BINARY_DIR}/aosuiteConfig.cmake
     "include(\${CMAKE_CURRENT_LIST_DIR}/aosuiteTargets.cmake)\n")
install(FILES ${PROJECT_BINARY_DIR}/aosuiteConfig.cmake
              ${PROJECT_BINARY_DIR}/aosuiteConfigVersion.cmake
        DESTINATION lib/cmake/aosuite)

# The Debian package: its dependencies are the packages of the libraries the installed files
# link (dpkg-shlibdeps), plus the Mesa drivers EGL opens at run time.
set(CPACK_PACKAGE_NAME aosuite)
set(CPACK_PACKAGE_CONTACT "aosuite developers <aosuite@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Perceptual image comparison and regression suite, with an ambient-occlusion bench")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR})
if(AOSUITE_RENDERER)
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "libgl1-mesa-dri")
endif()
set(CPACK_PACKAGE_INSTALL_DIRECTORY aosuite)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
include(CPack)
