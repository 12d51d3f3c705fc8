# Install rules and the Debian package. The layout (core/install_layout.h):
#   bin/shadowbench                          RUNPATH $ORIGIN/../lib/shadowbench
#   lib/shadowbench/lib*.so                  the driver's and the plugin API's libraries, and
#                                            the image codec module the driver loads beside them
#   lib/shadowbench/plugins/*.so             technique families, RUNPATH $ORIGIN/..
#   share/shadowbench/                       plot_charts.py, configs/ (with models/)
#   share/man/man1/shadowbench.1.gz, share/bash-completion/completions/shadowbench
#   share/doc/shadowbench/                   README.md and docs/
#   include/shadowbench/, lib/shadowbench/cmake/   the plugin API for families
#                                            built elsewhere (find_package(shadowbench))
#   lib/shadowbench/libshadowbench_shadow_kit.a, include/shadowbench/common/
#                                            the shadow-map kit they may link too
# Every path is relative, so a moved prefix works (tests/install/).
file(RELATIVE_PATH _bin_to_lib /p/${CMAKE_INSTALL_BINDIR} /p/${SHADOWBENCH_INSTALL_LIB_DIR})
set_target_properties(shadowbench PROPERTIES INSTALL_RPATH "$ORIGIN/${_bin_to_lib}")
set_target_properties(shadowbench_core shadowbench_plugin_api PROPERTIES INSTALL_RPATH "$ORIGIN")
get_property(_plugins GLOBAL PROPERTY SHADOWBENCH_PLUGINS)
set_target_properties(${_plugins} PROPERTIES INSTALL_RPATH "$ORIGIN/..")

install(TARGETS shadowbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS shadowbench_core LIBRARY DESTINATION ${SHADOWBENCH_INSTALL_LIB_DIR})
# Loaded from libshadowbench_core.so's folder (core/image_codec.h).
install(TARGETS shadowbench_image_codec LIBRARY DESTINATION ${SHADOWBENCH_INSTALL_LIB_DIR})
install(TARGETS shadowbench_plugin_api EXPORT shadowbench-plugin-api
        LIBRARY DESTINATION ${SHADOWBENCH_INSTALL_LIB_DIR})
# The shadow-map kit: a static library, linked into each plugin that uses it.
install(TARGETS shadowbench_shadow_kit EXPORT shadowbench-plugin-api
        ARCHIVE DESTINATION ${SHADOWBENCH_INSTALL_LIB_DIR})
install(TARGETS ${_plugins} LIBRARY DESTINATION ${SHADOWBENCH_INSTALL_PLUGIN_DIR})

install(FILES harness/results/plot_charts.py DESTINATION ${SHADOWBENCH_INSTALL_DATA_DIR})
install(DIRECTORY configs/ DESTINATION ${SHADOWBENCH_INSTALL_DATA_DIR}/configs)
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
# docs/ holds the example technique examples/my_pcf with its CMakeLists.txt.
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The man page (help2man, from --help-all and --version) and the bash
# completion (`shadowbench completion bash`), both generated from the
# parser by the binary just built. Not in sanitizer builds, which are never
# installed.
if(NOT SHADOWBENCH_SANITIZE)
  find_program(HELP2MAN help2man REQUIRED)
  set(_man ${CMAKE_BINARY_DIR}/share/man/man1/shadowbench.1)
  set(_completion ${CMAKE_BINARY_DIR}/share/bash-completion/completions/shadowbench)
  add_custom_command(
    OUTPUT ${_man}.gz
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/share/man/man1
    # The folders --help-all and --version print are the installed layout's,
    # under <prefix>, not this build tree's (nor the builder's plugin path).
    COMMAND ${CMAKE_COMMAND} -E env --unset=SHADOWBENCH_PLUGIN_PATH
            SHADOWBENCH_PLUGIN_DIR=<prefix>/${SHADOWBENCH_INSTALL_PLUGIN_DIR}
            SHADOWBENCH_SHARE_DIR=<prefix>/${SHADOWBENCH_INSTALL_DATA_DIR}
            ${HELP2MAN} --no-info --no-discard-stderr --help-option=--help-all
            "--name=benchmark shadow-rendering techniques headlessly"
            --include=${PROJECT_SOURCE_DIR}/cmake/shadowbench.h2m
            --output=${_man} $<TARGET_FILE:shadowbench>
    COMMAND gzip -9nf ${_man}
    DEPENDS shadowbench ${PROJECT_SOURCE_DIR}/cmake/shadowbench.h2m
    COMMENT "Generating the man page with help2man"
    VERBATIM)
  add_custom_command(
    OUTPUT ${_completion}
    COMMAND ${CMAKE_COMMAND} -DOUT=${_completion} -P ${PROJECT_SOURCE_DIR}/cmake/write_completion.cmake
            -- $<TARGET_FILE:shadowbench> completion bash
    DEPENDS shadowbench ${_plugins} ${PROJECT_SOURCE_DIR}/cmake/write_completion.cmake
    COMMENT "Generating the bash completion"
    VERBATIM)
  add_custom_target(shadowbench_man_and_completion ALL DEPENDS ${_man}.gz ${_completion})
  install(FILES ${_man}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
  install(FILES ${_completion} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
endif()

# The plugin API: its headers (core/, gl/, plugin/ and glad's), its library
# and a package config that finds its plugin folder relative to itself; and
# the shadow-map kit's headers beside them, so that "common/map_lookup.h"
# names the same file in a built-in family and in one built elsewhere.
foreach(part core gl plugin)
  install(DIRECTORY harness/${part}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shadowbench/${part}
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(DIRECTORY techniques/common/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shadowbench/common
        FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${GLAD_OUT}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shadowbench)
# <prefix>/lib/shadowbench/cmake/ is on find_package()'s search path.
set(_cmake_dir ${SHADOWBENCH_INSTALL_LIB_DIR}/cmake)
install(EXPORT shadowbench-plugin-api NAMESPACE shadowbench::
        FILE shadowbench-plugin-api-targets.cmake DESTINATION ${_cmake_dir})
file(RELATIVE_PATH _cmake_to_plugins /p/${_cmake_dir} /p/${SHADOWBENCH_INSTALL_PLUGIN_DIR})
set(SHADOWBENCH_CONFIG_PLUGIN_DIR "\${CMAKE_CURRENT_LIST_DIR}/${_cmake_to_plugins}")
configure_file(cmake/shadowbenchConfig.cmake.in ${CMAKE_BINARY_DIR}/install/shadowbenchConfig.cmake
               @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/install/shadowbenchConfig.cmake DESTINATION ${_cmake_dir})

# The Debian package: `cpack -G DEB` in the build folder writes
# shadowbench_<version>_amd64.deb. Its Depends are computed by dpkg-shlibdeps
# from the binaries, plus what the charts need at run time.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME shadowbench)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "shadowbench developers <shadowbench@users.noreply.github.com>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "headless batch benchmark of shadow-rendering techniques")
# One string: set() would join the lines as a list, with ';' (which dpkg
# then shows at the start of every continuation line). CPackDeb indents
# each line by one space, as a Description's continuation lines must be.
string(CONCAT CPACK_PACKAGE_DESCRIPTION
    "shadowbench renders JSON experiments (generated scenes or any glTF file) through\n"
    "every shadow technique plugin at every resolution, headlessly (OSMesa or EGL),\n"
    "and reports error against a ray-traced reference against run time.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The GL backends' libraries are opened, not linked (gl/context_*.cpp), so
# dpkg-shlibdeps cannot see them: OSMesa, the default backend, is named here.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-matplotlib, libosmesa6")
# EGL needs libglvnd's libEGL and Mesa's EGL driver.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl1, libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "openimageio-tools")
include(CPack)
