# Installation (docs/install.md): the binary, the man page, bash and zsh
# completion, libsessile as a static and a shared library, its public headers
# and a pkg-config file.  Two install components, which CPack turns into two
# Debian packages (cmake/Package.cmake): "runtime" (sessile) and "dev"
# (sessile-dev).
include(GNUInstallDirs)

# --- the shared library ------------------------------------------------------
# The same per-layer objects as libsessile.a, compiled position-independent
# once for both (no second compilation of every layer).  Without semantic
# interposition GCC keeps inlining the library's own global functions as in a
# non-PIC build.  Before 1.0 every minor version may change the ABI, so the
# SONAME carries major.minor (libsessile.so.0.1).
foreach(t ${SESSILE_LAYER_TARGETS})
  set_target_properties(${t} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${t} PRIVATE -fno-semantic-interposition)
endforeach()
add_library(sessile_shared SHARED ${SESSILE_LIB_OBJECTS})
set_target_properties(sessile_shared PROPERTIES
  OUTPUT_NAME sessile LINKER_LANGUAGE CXX
  VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
target_link_libraries(sessile_shared PRIVATE sessile_deps)

# --- what is installed ------------------------------------------------------------
install(TARGETS sessile RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(TARGETS sessile_shared
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev)
install(TARGETS sessile_lib ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY host/include/sessile DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev
  FILES_MATCHING PATTERN "*.h")
# Written by hand, not by help2man (docs/install.md says why).
install(FILES docs/sessile.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
install(FILES tools/completion/sessile.bash DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
  RENAME sessile COMPONENT runtime)
install(FILES tools/completion/_sessile DESTINATION ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions
  COMPONENT runtime)

# --- pkg-config --------------------------------------------------------------------
# The prefix is the one installed into, known only at install time
# (`cmake --install build --prefix DIR`; /usr in the Debian packages), so the
# file is configured twice: now with everything else, then by the install
# step with the prefix.  Requires: what the public headers include
# (cjson/cJSON.h); the rest is only needed to link libsessile.a
# (`pkg-config --static`).
set(SESSILE_PC_PREFIX "@CMAKE_INSTALL_PREFIX@")
configure_file(cmake/sessile.pc.in ${CMAKE_CURRENT_BINARY_DIR}/sessile.pc.in @ONLY)
install(CODE "configure_file(\"${CMAKE_CURRENT_BINARY_DIR}/sessile.pc.in\"
                             \"${CMAKE_CURRENT_BINARY_DIR}/pkgconfig/sessile.pc\" @ONLY)"
  COMPONENT dev)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pkgconfig/sessile.pc
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
