# sessile_embed_shaders(OUT_VAR SHADER_DIR)
# Every shaders/<layer>/kernels.def declares that layer's kernels (docs/design.md,
# "Declaring a kernel").  Per layer, the host tool sessile_kernelgen writes
# <layer>_kernels.h/.c (descriptor table, push structs, constants) and
# <layer>_kernels.glsl (push blocks, bindings, the same constants) into
# ${CMAKE_CURRENT_BINARY_DIR}/kernels.  Every declared kernel's <name>.comp is
# compiled with glslangValidator into a C array, twice (f64 and f32) or once,
# with SESSILE_KERNEL_<layer>_<name> defined so the layer's GLSL include picks
# its declarations; spirv_table.c lists them all by name: the one table of
# embedded kernels.  OUT_VAR gets every generated source and header.
function(sessile_embed_shaders out_var shader_dir)
  set(gen ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  set(kgen ${CMAKE_CURRENT_BINARY_DIR}/kernels)
  file(MAKE_DIRECTORY ${gen} ${kgen})
  file(GLOB defs CONFIGURE_DEPENDS ${shader_dir}/*/kernels.def)
  list(SORT defs)
  set(outputs)
  set(includes "")
  set(entries "")
  set(declared)
  foreach(def ${defs})
    get_filename_component(dir ${def} DIRECTORY)
    get_filename_component(layer ${dir} NAME)
    set(kout ${kgen}/${layer}_kernels.h ${kgen}/${layer}_kernels.c ${kgen}/${layer}_kernels.glsl)
    add_custom_command(
      OUTPUT ${kout}
      COMMAND sessile_kernelgen ${def} ${layer} ${kgen}
      DEPENDS sessile_kernelgen ${def}
      COMMENT "kernels.def -> ${layer}_kernels.{h,c,glsl}"
      VERBATIM)
    list(APPEND outputs ${kout})
    # "kernel ID NAME real|once ..." lines: what to compile, and how often.
    file(STRINGS ${def} klines REGEX "^kernel[ \t]")
    foreach(kl ${klines})
      string(REGEX MATCH "^kernel[ \t]+[A-Za-z0-9_]+[ \t]+([A-Za-z0-9_]+)[ \t]+(real|once)" ok "${kl}")
      if(NOT ok)
        message(FATAL_ERROR "${def}: cannot read \"${kl}\"")
      endif()
      set(base ${layer}/${CMAKE_MATCH_1})
      set(precs f64 f32)
      if(CMAKE_MATCH_2 STREQUAL "once")
        set(precs once)
      endif()
      list(APPEND declared ${base}.comp)
      string(MAKE_C_IDENTIFIER "${base}" kid)
      foreach(prec ${precs})
        set(name ${base}.${prec})
        set(def_f64 -DSESSILE_F64=1)
        if(prec STREQUAL "f32")
          set(def_f64 -DSESSILE_F64=0)
        elseif(prec STREQUAL "once")
          set(name ${base})
          set(def_f64)
        endif()
        string(MAKE_C_IDENTIFIER "sessile_spv_${name}" ident)
        set(hdr ${gen}/${ident}.h)
        add_custom_command(
          OUTPUT ${hdr}
          COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 ${def_f64} -DSESSILE_KERNEL_${kid}=1
                  -I${shader_dir}/common -I${kgen} --vn ${ident} --depfile ${hdr}.d
                  -o ${hdr} ${shader_dir}/${base}.comp
          DEPENDS ${shader_dir}/${base}.comp ${kgen}/${layer}_kernels.glsl
          DEPFILE ${hdr}.d
          COMMENT "GLSL ${base}.comp (${prec})"
          VERBATIM)
        list(APPEND outputs ${hdr})
        string(APPEND includes "#include \"${ident}.h\"\n")
        string(APPEND entries "  {\"${name}\", ${ident}, sizeof ${ident}},\n")
      endforeach()
    endforeach()
  endforeach()
  # Graphics shaders (shaders/render/*.vert, *.frag: the renderer's, not
  # kernels) are compiled once each and listed by file name ("render/mesh.vert").
  file(GLOB gfx CONFIGURE_DEPENDS ${shader_dir}/render/*.vert ${shader_dir}/render/*.frag)
  list(SORT gfx)
  foreach(src ${gfx})
    file(RELATIVE_PATH name ${shader_dir} ${src})
    string(MAKE_C_IDENTIFIER "sessile_spv_${name}" ident)
    set(hdr ${gen}/${ident}.h)
    add_custom_command(
      OUTPUT ${hdr}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 -I${shader_dir}/render
              --vn ${ident} --depfile ${hdr}.d -o ${hdr} ${src}
      DEPENDS ${src}
      DEPFILE ${hdr}.d
      COMMENT "GLSL ${name}"
      VERBATIM)
    list(APPEND outputs ${hdr})
    string(APPEND includes "#include \"${ident}.h\"\n")
    string(APPEND entries "  {\"${name}\", ${ident}, sizeof ${ident}},\n")
  endforeach()
  # A .comp without a declaration would silently not be built: refuse it.
  file(GLOB_RECURSE comps CONFIGURE_DEPENDS RELATIVE ${shader_dir} ${shader_dir}/*.comp)
  foreach(rel ${comps})
    if(NOT rel IN_LIST declared)
      message(FATAL_ERROR "shaders/${rel} has no kernel line in its layer's kernels.def")
    endif()
  endforeach()
  # The include files, for GLSL compiled at run time (host/gpu/glsl_compile.c):
  # every shaders/<layer>/*.glsl and the generated <layer>_kernels.glsl.
  file(GLOB incs CONFIGURE_DEPENDS ${shader_dir}/*/*.glsl)
  list(SORT incs)
  set(kglsl)
  foreach(def ${defs})
    get_filename_component(dir ${def} DIRECTORY)
    get_filename_component(layer ${dir} NAME)
    list(APPEND kglsl ${kgen}/${layer}_kernels.glsl)
  endforeach()
  set(srcs_c ${gen}/glsl_sources.c)
  add_custom_command(
    OUTPUT ${srcs_c}
    COMMAND ${CMAKE_COMMAND} "-DOUT=${srcs_c}" "-DFILES=${incs};${kglsl}" -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedGlslIncludes.cmake
    DEPENDS ${incs} ${kglsl} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedGlslIncludes.cmake
    COMMENT "GLSL include files -> glsl_sources.c"
    VERBATIM)
  list(APPEND outputs ${srcs_c})
  set(table ${gen}/spirv_table.c)
  file(CONFIGURE OUTPUT ${table} CONTENT
"/* Generated by cmake/EmbedShaders.cmake: every embedded kernel, by name. */
#include <string.h>
#include \"sessile/gpu/gpu.h\"
${includes}
static const sessile_spirv table[] = {
${entries}};

const sessile_spirv *sessile_spirv_find(const char *name) {
  for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
    if (strcmp(table[i].name, name) == 0) return &table[i];
  return NULL;
}
")
  set(${out_var} ${table} ${outputs} PARENT_SCOPE)
endfunction()
