# install_rules.cmake: what `cmake --install` puts under the prefix, and the Debian package `cpack` makes of it.
#
#   <prefix>/bin/lucent                      the command-line tool
#   <prefix>/<libdir>/liblucent.so.<soversion>  the library: the static libraries linked whole into one shared object
#                                               (shaders and the default scene are embedded in it)
#   <prefix>/include/lucent/*.h              the public headers
#   <prefix>/<libdir>/cmake/lucent/          find_package(lucent CONFIG): the imported target lucent::lucent
#   <prefix>/<libdir>/pkgconfig/lucent.pc    pkg-config --cflags --libs lucent
#   <prefix>/share/lucent/scenes/            the example scenes
#   <prefix>/<python dir>/lucent.*.so        the Python module (python/CMakeLists.txt), where that prefix's Python
#                                            finds it: lib/python3/dist-packages under /usr (Debian's packaged
#                                            modules), lib/python3.X/dist-packages under any other prefix (Debian's
#                                            /usr/local scheme), or the interpreter's own scheme elsewhere; the
#                                            folder is chosen when installing, from the prefix given then.
# Everything is relocatable: `cmake --install build --prefix DIR` anywhere gives working package files.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

if(LUCENT_SANITIZE OR LUCENT_FUZZ)
  return()  # sanitized trees are for tests only
endif()

# ---- the shared library ------------------------------------------------------------------------------------------
# Every object of the three static libraries (their own dependencies become the shared object's DT_NEEDED);
# consumers see the public headers, glm and nlohmann_json (scene_writer.h), nothing else.
set(LUCENT_SOVERSION "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")  # before 1.0 a minor version breaks ABI
add_library(lucent_shared SHARED src/library/shared_library.cpp $<TARGET_OBJECTS:lucent_core>
            $<TARGET_OBJECTS:lucent_gl> $<TARGET_OBJECTS:lucent_reference>)
set_target_properties(lucent_core lucent_gl lucent_reference lucent_vdb lucent_cgal
                      PROPERTIES POSITION_INDEPENDENT_CODE ON)
set_target_properties(lucent_shared PROPERTIES OUTPUT_NAME lucent EXPORT_NAME lucent
                      VERSION "${PROJECT_VERSION}" SOVERSION "${LUCENT_SOVERSION}")
target_link_libraries(lucent_shared
  PRIVATE lucent_gl lucent_reference lucent_core lucent_warnings  # their dependencies (the objects are above)
  PUBLIC glm::glm nlohmann_json::nlohmann_json)
target_link_options(lucent_shared PRIVATE "LINKER:--no-undefined")  # a missing symbol fails here, not in a user's link
target_include_directories(lucent_shared PUBLIC "$<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/include>"
                           "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
target_compile_definitions(lucent_shared PUBLIC GLM_FORCE_CXX17)
target_compile_features(lucent_shared PUBLIC cxx_std_20)

# ---- what is installed ---------------------------------------------------------------------------------------------
install(TARGETS lucent_cli RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(TARGETS lucent_shared EXPORT lucentTargets
        LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" NAMELINK_COMPONENT Unspecified)
install(DIRECTORY include/lucent DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" FILES_MATCHING PATTERN "*.h")

set(LUCENT_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/lucent")
install(EXPORT lucentTargets NAMESPACE lucent:: DESTINATION "${LUCENT_CMAKE_DIR}")
configure_package_config_file(cmake/lucentConfig.cmake.in "${CMAKE_BINARY_DIR}/install/lucentConfig.cmake"
                              INSTALL_DESTINATION "${LUCENT_CMAKE_DIR}")
write_basic_package_version_file("${CMAKE_BINARY_DIR}/install/lucentConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_BINARY_DIR}/install/lucentConfig.cmake" "${CMAKE_BINARY_DIR}/install/lucentConfigVersion.cmake"
        DESTINATION "${LUCENT_CMAKE_DIR}")

# pkg-config: the prefix from the file's own place (${pcfiledir}), so that an install under another prefix works.
set(LUCENT_PKGCONFIG_DIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
file(RELATIVE_PATH LUCENT_PKGCONFIG_TO_PREFIX "/prefix/${LUCENT_PKGCONFIG_DIR}" "/prefix")
configure_file(cmake/lucent.pc.in "${CMAKE_BINARY_DIR}/install/lucent.pc" @ONLY)
install(FILES "${CMAKE_BINARY_DIR}/install/lucent.pc" DESTINATION "${LUCENT_PKGCONFIG_DIR}")
install(FILES README.md DESTINATION "${CMAKE_INSTALL_DOCDIR}")
# The example scenes with their maps, volumes and environment maps (the bunny and horse meshes are glmark2-data's).
install(DIRECTORY scenes/ DESTINATION "${CMAKE_INSTALL_DATADIR}/lucent/scenes")

# ---- the Debian package: cpack -G DEB (in the build folder), installing under /usr ---------------------------------
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lucent)
set(CPACK_PACKAGE_VENDOR lucent)
set(CPACK_PACKAGE_CONTACT "lucent developers <lucent@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "real-time subsurface scattering for translucent materials, with CPU ground truth")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # the shared libraries' packages, from dpkg-shlibdeps
# The headers' own dependencies and the Python module's (the interpreter it was built for, numpy).
# libepoxy opens libEGL and libGL at run time (no DT_NEEDED for dpkg-shlibdeps to see).
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libgl1, libglm-dev, nlohmann-json3-dev")
# An EGL driver: Mesa's llvmpipe renders without a GPU; a GPU's vendor driver replaces it.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "glmark2-data")  # the bunny and horse meshes of the example scenes
if(LUCENT_PYTHON_MODULE_DEPENDS)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", ${LUCENT_PYTHON_MODULE_DEPENDS}")
endif()
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "lucent renders translucent materials (marble, milk, skin, wax) in real time with physically based\n subsurface scattering and measures each method against CPU ground truth. This package holds the\n command-line tool, the shared library with its headers, CMake package and pkg-config file, and the\n Python module.")
include(CPack)
