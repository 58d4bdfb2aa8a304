/* sessile — Vulkan compute runtime: device choice, buffers, kernels, command
 * recording, timestamps, pipeline cache.
 *
 * Objects are opaque with create/destroy pairs; destroy(NULL) is a no-op.
 * A context owns nothing created from it: destroy buffers, kernels and
 * command recorders before the context. */
#ifndef SESSILE_GPU_H
#define SESSILE_GPU_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_gpu sessile_gpu;
typedef struct sessile_buffer sessile_buffer;
typedef struct sessile_kernel sessile_kernel;
typedef struct sessile_cmd sessile_cmd;

/* A Vulkan validation-layer message: is_error 1 for an error, 0 for a
 * warning; user is the options' validation_user. */
typedef void (*sessile_validation_fn)(void *user, int is_error, const char *message);

typedef struct sessile_gpu_options {
  /* The library reads no environment variable: the CLI fills these from
   * SESSILE_DEVICE, SESSILE_VALIDATION, SESSILE_PRECISION, SESSILE_STAGED,
   * XDG_CACHE_HOME and HOME (host/cli/cli_gpu_env.h). */
  /* Device by index or case-insensitive name substring; NULL: the best
   * (discrete > integrated > virtual > CPU). */
  const char *device;
  /* Enable VK_LAYER_KHRONOS_validation: 1 yes, 0 or -1 (unchosen) no. */
  int validation;
  /* Krylov vector precision: 64, 32, or 0 = 64 where the device has
   * shaderFloat64. */
  int precision;
  /* 1: take a discrete GPU's paths on unified memory too (device buffers
   * unmapped, every transfer staged), so that lavapipe covers them. */
  int staged;
  /* Pipeline cache folder, the caller's choice (resolved once with
   * realpath); NULL: cache_default; "" disables the on-disk cache. */
  const char *cache_dir;
  /* The default cache folder (the CLI's: $XDG_CACHE_HOME/sessile or
   * ~/.cache/sessile), created 0700 and not used when it is a symlink;
   * NULL: no on-disk cache unless cache_dir names one. */
  const char *cache_default;
  /* Where validation warnings and errors go once counted
   * (sessile_gpu_validation_count).  NULL (the default): printed to stderr
   * as "sessile: vulkan validation error|warning: MESSAGE", the line the
   * tests and `--validation` rely on; a callback replaces the printing (it
   * may run on any thread that calls Vulkan). */
  sessile_validation_fn validation_message;
  void *validation_user;
} sessile_gpu_options;

/* Fills the defaults above. */
void sessile_gpu_options_default(sessile_gpu_options *o);

typedef struct sessile_gpu_info {
  char name[256];
  char type[24];   /* "discrete", "integrated", "virtual", "cpu", "other" */
  char driver[520]; /* driver name and info */
  uint32_t api_version, vendor_id, device_id, index;
  uint32_t subgroup_size;
  int subgroup_arithmetic; /* subgroup BASIC + ARITHMETIC ops in compute shaders */
  int float64;     /* shaderFloat64 */
  int precision;   /* chosen Krylov precision: 32 or 64 */
  uint64_t max_storage_buffer_range;
  uint32_t max_texel_buffer_elements; /* maxTexelBufferElements */
  uint32_t max_workgroup_invocations;
  uint32_t max_workgroup_count_x;
  double timestamp_period_ns;
  int unified_memory; /* device-local memory is host-visible */
  uint64_t device_local_bytes; /* the largest device-local heap */
} sessile_gpu_info;

sessile_status sessile_gpu_create(const sessile_gpu_options *opt, sessile_gpu **out);
void sessile_gpu_destroy(sessile_gpu *g);
const sessile_gpu_info *sessile_gpu_info_of(const sessile_gpu *g);
/* Queue submissions so far: recordings and blocking transfers (each waits,
 * about 0.1 ms on a discrete GPU); for tests and benchmarks that count them. */
uint64_t sessile_gpu_submissions(const sessile_gpu *g);

/* Device time per kernel, from timestamps around each dispatch (for
 * benchmarks: `sessile bench sds --kernels`).  sessile_gpu_profile(g, 1)
 * clears the table and times the dispatches of every recording begun from
 * then on, (g, 0) stops; the first SESSILE_PROFILE_MAX dispatches of a recording are timed,
 * the others counted as untimed.  A timed dispatch ends at the next
 * dispatch's barrier as before, so results are unchanged.  Fails with
 * SESSILE_ERR_UNSUPPORTED on a queue without timestamps. */
#define SESSILE_PROFILE_MAX 4096 /* dispatches timed per recording (a GMRES segment holds ~2 400) */
typedef struct sessile_kernel_time {
  char name[64];
  uint64_t calls;
  double ms; /* summed over its calls */
} sessile_kernel_time;
sessile_status sessile_gpu_profile(sessile_gpu *g, int on);
/* The table (entries in first-dispatch order; valid until the next
 * sessile_gpu_profile or destroy) and the count of untimed dispatches. */
size_t sessile_gpu_profile_read(const sessile_gpu *g, const sessile_kernel_time **out, uint64_t *untimed);

/* Number of validation-layer warnings and errors seen so far (tests fail on > 0). */
uint64_t sessile_gpu_validation_count(const sessile_gpu *g);

/* Prints every Vulkan device with type, driver, heaps, subgroup size, fp64 and
 * the limits that matter; marks the one that would be chosen. */
sessile_status sessile_gpu_print_devices(FILE *out, const char *device_choice);
/* Whether device_choice (NULL or "": $SESSILE_DEVICE) names an existing
 * device, without creating one: SESSILE_ERR_USAGE ("no device name contains
 * ...", "device index 7 does not exist ...") when it names none, else
 * SESSILE_OK (also with no Vulkan at all: that is reported where a device is
 * made).  For a command to refuse a bad choice before it writes anything. */
sessile_status sessile_gpu_check_device(const char *device_choice);

/* --- buffers ----------------------------------------------------------- */
typedef enum sessile_buffer_kind {
  SESSILE_BUFFER_DEVICE = 0, /* device-local; staged transfers unless unified */
  SESSILE_BUFFER_MAPPED = 1  /* host-visible + coherent, persistently mapped */
} sessile_buffer_kind;

/* A storage buffer of `bytes` (> 0).  Fails with SESSILE_ERR_TOO_LARGE over
 * maxStorageBufferRange.  Contents start zeroed. */
sessile_status sessile_buffer_create(sessile_gpu *g, size_t bytes, sessile_buffer_kind kind,
                                     sessile_buffer **out);
void sessile_buffer_destroy(sessile_buffer *b);
/* Makes *b (NULL or a buffer of this kind) hold at least `bytes`: kept when
 * it does, else replaced by a zeroed buffer with a quarter more room (within
 * maxStorageBufferRange), so that a size growing in small steps (an organism
 * dividing cell by cell) reallocates a logarithmic number of times; on a
 * discrete GPU each allocation is a driver call of up to a millisecond. */
sessile_status sessile_buffer_reserve(sessile_gpu *g, sessile_buffer **b, size_t bytes, sessile_buffer_kind kind);
size_t sessile_buffer_size(const sessile_buffer *b); /* 0 for NULL (a buffer not made yet) */
/* Does a whole-buffer view of texels of texel_bytes fit maxTexelBufferElements
 * (NULL: yes)?  A kernel's _tex variant is taken only when every view does. */
int sessile_buffer_texels_fit(const sessile_buffer *b, size_t texel_bytes);
/* Host pointer of a MAPPED buffer (or of a DEVICE one on unified memory); NULL otherwise. */
void *sessile_buffer_host_ptr(sessile_buffer *b);
/* Blocking transfers (wait for the device to be idle with respect to them). */
sessile_status sessile_buffer_upload(sessile_buffer *b, size_t offset, const void *src, size_t bytes);
sessile_status sessile_buffer_download(sessile_buffer *b, size_t offset, void *dst, size_t bytes);
/* n reals at real offset offset_reals, in the context's precision (8-byte
 * doubles on fp64 contexts, 4-byte floats on fp32 ones, converted here); the
 * host side is always double. */
sessile_status sessile_buffer_upload_reals(sessile_buffer *b, size_t offset_reals, const double *src,
                                           size_t n);
sessile_status sessile_buffer_download_reals(sessile_buffer *b, size_t offset_reals, double *dst,
                                             size_t n);

/* --- kernels ----------------------------------------------------------- */
/* How a binding is read: a storage buffer, or a uniform texel buffer
 * (texelFetch on a usamplerBuffer) of the given format.  For a texel binding
 * a view of the whole buffer is made on first use and kept with the buffer;
 * the buffer must hold at most max_texel_buffer_elements texels.  Why: lavapipe
 * gathers texels with vector loads but scalarises storage-buffer loads per
 * lane, which made SpMV ~2.5x slower (docs/performance.md). */
typedef enum sessile_binding_kind {
  SESSILE_BINDING_STORAGE = 0,
  SESSILE_TEXEL_R32UI = 1,    /* 4-byte texels */
  SESSILE_TEXEL_RG32UI = 2,   /* 8-byte texels */
  SESSILE_TEXEL_RGBA32UI = 3, /* 16-byte texels */
  SESSILE_TEXEL_REAL = 4      /* one texel per real: R32UI (fp32) or RG32UI (fp64) */
} sessile_binding_kind;

typedef struct sessile_binding_decl {
  const char *name;          /* the GLSL name */
  sessile_binding_kind kind;
  int readonly;              /* the kernel never writes it */
} sessile_binding_decl;

/* The most bindings a kernel declares (one descriptor set). */
#define SESSILE_MAX_BINDINGS 24

/* One kernel's declaration.  Written by tools/kernelgen.c from
 * shaders/<layer>/kernels.def into sessile_<layer>_kernels[] (<layer>_kernels.h),
 * together with the GLSL push block and bindings, so host and shader agree
 * (docs/design.md, "Declaring a kernel"). */
typedef struct sessile_kernel_decl {
  const char *name;          /* "la/axpy": SPIR-V "la/axpy.f64"/".f32", or "la/axpy" when once */
  uint32_t nbindings;        /* bindings 0..nbindings-1 */
  const sessile_binding_decl *bindings;
  uint32_t push_bytes;       /* sizeof the generated push struct, 0 for none */
  uint32_t local_size;       /* default workgroup size x (a power of two) */
  int per_precision;         /* 1: compiled for f64 and f32; 0: once */
} sessile_kernel_decl;

/* A push-constant field of GLSL type REAL: double on fp64 contexts, float on
 * fp32 ones; 8 bytes and 8-aligned either way so offsets do not move. */
typedef union sessile_push_real {
  double d;
  float f;
} sessile_push_real;
static inline sessile_push_real sessile_push_real_of(double v, uint32_t real_bytes) {
  sessile_push_real r = {0};
  if (real_bytes == 8) r.d = v;
  else r.f = (float)v;
  return r;
}

/* A compute pipeline for declaration `d` in precision real_bytes (8 or 4; 0:
 * the context's).  local_size overrides d->local_size when non-zero; it is
 * halved until it fits maxComputeWorkGroupInvocations and
 * maxComputeWorkGroupSize[0] (kernels with reductions need a power of two).
 * The workgroup size reaches the shader as specialisation constant 0. */
sessile_status sessile_kernel_create_decl(sessile_gpu *g, const sessile_kernel_decl *d,
                                          uint32_t real_bytes, uint32_t local_size,
                                          sessile_kernel **out);
void sessile_kernel_destroy(sessile_kernel *k);
uint32_t sessile_kernel_local_size(const sessile_kernel *k);

/* --- command recording -------------------------------------------------- */
sessile_status sessile_cmd_create(sessile_gpu *g, sessile_cmd **out);
void sessile_cmd_destroy(sessile_cmd *c);
/* A recording that its own kernels may cut short (docs/design.md, "Indirect
 * dispatch"): from here on, a dispatch of one of the n group counts reads
 * its counts from `args` (uint words: [0] the counts kept, then from word 4
 * three per count, x y z), uploaded here; a kernel that writes 0 into a
 * count's x skips every later dispatch of that count without launching
 * it (a zero-sized dispatch: lavapipe then wakes no thread).  Other counts
 * dispatch as before.  Before the recording's first dispatch; args needs
 * (4 + 3 SESSILE_INDIRECT_MAX) words.  Ends with the recording. */
#define SESSILE_INDIRECT_MAX 16
sessile_status sessile_cmd_indirect(sessile_cmd *c, sessile_buffer *args, const uint32_t *groups, uint32_t n);
/* Starts a fresh recording (drops the previous one). */
sessile_status sessile_cmd_begin(sessile_cmd *c);
/* Records a dispatch of `groups` workgroups (split into 2-D when above
 * maxComputeWorkGroupCount[0]; kernels read their index with sessile_gid()).
 * A compute->compute barrier precedes every dispatch but the first. */
sessile_status sessile_cmd_dispatch(sessile_cmd *c, const sessile_kernel *k, uint32_t groups,
                                    sessile_buffer *const *buffers, const void *push);
/* Records a copy of the first `bytes` of src into dst between dispatches:
 * after everything recorded before it, before every dispatch after it (on
 * lavapipe a copy is the queue thread's memcpy, no thread-pool round trip
 * as a dispatch is).  Not after a recorded download. */
sessile_status sessile_cmd_copy(sessile_cmd *c, sessile_buffer *src, sessile_buffer *dst, size_t bytes);
/* Records a GPU timestamp into slot (0..63) after all previous work. */
sessile_status sessile_cmd_timestamp(sessile_cmd *c, uint32_t slot);
sessile_status sessile_cmd_end(sessile_cmd *c);
/* Transfers inside a recording, so that a loop which moves a few arrays a
 * step pays one submission a step, not one per array (on a discrete GPU each
 * blocking transfer is a submission and a wait of about 0.1 ms).  Uploads come
 * before the recording's first dispatch: src is copied when the call is made
 * (into a mapped buffer at once, else into the recording's own staging
 * buffer, copied to the device when the recording runs).  Downloads come after
 * its last dispatch: dst (which must stay valid) is written by each
 * sessile_cmd_submit_wait.  Out of that order, or a second submission of a
 * recording with uploads, they fail with SESSILE_ERR_INTERNAL.  The _reals variants convert as
 * sessile_buffer_upload_reals does. */
sessile_status sessile_cmd_upload(sessile_cmd *c, sessile_buffer *b, size_t offset, const void *src, size_t bytes);
sessile_status sessile_cmd_download(sessile_cmd *c, sessile_buffer *b, size_t offset, void *dst, size_t bytes);
sessile_status sessile_cmd_upload_reals(sessile_cmd *c, sessile_buffer *b, size_t offset_reals, const double *src,
                                        size_t n);
sessile_status sessile_cmd_download_reals(sessile_cmd *c, sessile_buffer *b, size_t offset_reals, double *dst,
                                          size_t n);
/* Is a recording open (begun and not ended)? */
int sessile_cmd_recording(const sessile_cmd *c);
/* Submits the recording and waits; can be called again to re-run it. */
sessile_status sessile_cmd_submit_wait(sessile_cmd *c);
/* Nanoseconds between two timestamp slots of the last submitted run. */
sessile_status sessile_cmd_elapsed_ns(sessile_cmd *c, uint32_t slot0, uint32_t slot1, double *ns);

/* --- embedded SPIR-V table ---------------------------------------------- */
typedef struct sessile_spirv {
  const char *name;
  const uint32_t *code;
  size_t bytes;
} sessile_spirv;
/* The kernel named `name`, or NULL. */
const sessile_spirv *sessile_spirv_find(const char *name);

/* The shaders' include files (shaders/<layer>/NAME.glsl, shaders/common/NAME.glsl
 * and the generated <layer>_kernels.glsl), embedded at build time for GLSL
 * compiled at run time: the text of `name` ("rules_vm.glsl"), or NULL. */
const char *sessile_glsl_source_find(const char *name);

/* GLSL compiled at run time by glslang's library (docs/gpu.md, "Kernels
 * compiled at run time"): `body` is a compute shader without its #version
 * line, whose #include "name" lines resolve to sessile_glsl_source_find's
 * files (each once).  It is compiled as the build compiles d's .comp
 * (SESSILE_F64 and SESSILE_KERNEL_<d's name> defined, Vulkan 1.1 SPIR-V),
 * then made a pipeline as sessile_kernel_create_decl makes one.  A shader
 * that does not compile is SESSILE_ERR_INTERNAL with glslang's log. */
sessile_status sessile_kernel_create_glsl(sessile_gpu *g, const sessile_kernel_decl *d, uint32_t real_bytes,
                                          uint32_t local_size, const char *body, sessile_kernel **out);
/* The SPIR-V of such a shader alone (no device): *words malloc'ed, *n its
 * 32-bit words; for tests and the fuzzer.  log: glslang's messages on
 * failure (may be NULL). */
sessile_status sessile_glsl_to_spirv(const char *kernel_name, int f64, const char *body, uint32_t **words,
                                     size_t *n, char *log, size_t nlog);

/* Monotonic wall clock in seconds. */
double sessile_wall_seconds(void);

#ifdef __cplusplus
}
#endif
#endif
