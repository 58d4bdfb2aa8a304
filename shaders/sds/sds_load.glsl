// Reads of the SDS kernels' read-only inputs, one macro per array: through
// uniform texel buffers (SDS_TEXEL = 1: lavapipe fetches texels with vector
// loads but scalarises storage-buffer loads per lane with a bounds check
// each, docs/design.md) or through storage buffers (SDS_TEXEL = 0: for a
// device whose maxTexelBufferElements a buffer exceeds).  The same bits
// either way.  Each kernel has a .comp per variant (NAME.comp, NAME_tex.comp)
// that includes its body NAME.glsl; the bindings of the texel variant are
// named with a _t (shaders/sds/kernels.def).
#ifndef SDS_LOAD_GLSL
#define SDS_LOAD_GLSL
#ifndef SDS_TEXEL
#error "define SDS_TEXEL (0 or 1) before including sds_load.glsl"
#endif
#if SDS_TEXEL
#include "texel_real.glsl"
#define LD_X(i) texel_real(x_t, (i))
#define LD_V(i) texel_real(v_t, (i))
#define LD_RM(i) texel_real(rm_t, (i))
#define LD_SM(i) texel_real(sm_t, (i))
#define LD_ELF(i) texel_real(elf_t, (i))
#define LD_WORLD(i) texel_real(world_t, (i))
#define LD_FSPH(i) texel_real(fsph_t, (i))
#define LD_TOPO(i) texelFetch(topo_t, int(i)).x
#define LD_LIST(i) texelFetch(list_t, int(i)).x
#define LD_OBS(i) texelFetch(obs_tri_t, int(i)).x
#define LD_HASH(i) texelFetch(hash_t, int(i)).x
#else
#define LD_X(i) x[i]
#define LD_V(i) v[i]
#define LD_RM(i) rm[i]
#define LD_SM(i) sm[i]
#define LD_ELF(i) elf[i]
#define LD_WORLD(i) world[i]
#define LD_FSPH(i) fsph[i]
#define LD_TOPO(i) topo[i]
#define LD_LIST(i) list[i]
#define LD_OBS(i) obs_tri[i]
#define LD_HASH(i) hash[i]
#endif
#endif
