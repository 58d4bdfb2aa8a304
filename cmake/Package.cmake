# Debian packages by CPack (`cpack -G DEB` in the build folder; checked by
# tools/test_deb.sh; docs/install.md):
#   sessile      the binary, libsessile.so.X.Y, the man page, completion
#   sessile-dev  headers, libsessile.a, the libsessile.so link, sessile.pc
# Depends are written out, not found by dpkg-shlibdeps: the Vulkan driver
# (mesa-vulkan-drivers: lavapipe, so a machine without a GPU runs) is loaded
# at run time and no ELF file names it.  tools/test_deb.sh checks that every
# library the binary and libsessile.so load belongs to a listed package.
set(CPACK_PACKAGE_NAME sessile)
set(CPACK_PACKAGE_VENDOR "sessile")
set(CPACK_PACKAGE_CONTACT "sessile maintainers <sessile@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "grows 3-D models of marine sponges and corals from physics on Vulkan")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_CURRENT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME sessile)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS
  "libc6, libstdc++6, libgcc-s1, libgomp1, libvulkan1, mesa-vulkan-drivers, libopenexr-3-1-30, libcjson1, libmuparser2v5, libcairo2, libpng16-16, zlib1g, libtet1.5, fonts-dejavu-core")
# the shlibs file and the ldconfig trigger for libsessile.so.X.Y
set(CPACK_DEBIAN_RUNTIME_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME sessile-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
  "sessile (= ${PROJECT_VERSION}), pkgconf | pkg-config, libcjson-dev, libvulkan-dev, libopenexr-dev, libmuparser-dev, libcairo2-dev, libpng-dev, zlib1g-dev, libtet1.5-dev, glslang-dev, spirv-tools")
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION "the sessile command, libsessile.so, man page and shell completion")
set(CPACK_COMPONENT_DEV_DESCRIPTION "libsessile's headers, static library and pkg-config file")
include(CPack)
