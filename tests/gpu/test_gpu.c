/* Tests of the Vulkan compute runtime (host/include/sessile/gpu/gpu.h): device
 * info, device choice and its errors, buffers (round trips at offsets, the
 * size limits and their messages), kernels from the embedded SPIR-V table,
 * command recording with a dispatch and timestamps, transfers recorded inside
 * a submission (uploads, a dispatch, downloads, their order enforced), and
 * destroy(NULL).
 * Every check prints what it compared; the exit status is non-zero if any
 * check failed or the validation layer reported anything. */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "gpu/gpu_internal.h"
#include "la_kernels.h" /* the generated declaration of la/fill */
#include "testutil.h"

/* Deterministic pseudo-random bytes (splitmix64). */
static void random_bytes(unsigned char *p, size_t n, uint64_t seed) {
  uint64_t s = seed;
  for (size_t i = 0; i < n; i++) {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    p[i] = (unsigned char)(z ^ (z >> 31));
  }
}

static int all_zero(const unsigned char *p, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (p[i]) return 0;
  return 1;
}

static void test_info(sessile_gpu *g) {
  printf("-- device info\n");
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  printf("   name \"%s\", type %s, subgroup %u, fp64 %d, precision %d, maxStorageBufferRange %" PRIu64
         ", maxComputeWorkGroupInvocations %u, maxComputeWorkGroupCount[0] %u, timestamp period %g ns, "
         "unified %d\n",
         i->name, i->type, i->subgroup_size, i->float64, i->precision, i->max_storage_buffer_range,
         i->max_workgroup_invocations, i->max_workgroup_count_x, i->timestamp_period_ns,
         i->unified_memory);
  t_true("info: device name is non-empty", i->name[0] != '\0');
  static const char *types[] = {"discrete", "integrated", "virtual", "cpu", "other"};
  int type_ok = 0;
  for (size_t k = 0; k < sizeof types / sizeof types[0]; k++) type_ok |= strcmp(i->type, types[k]) == 0;
  t_true("info: type is one of discrete/integrated/virtual/cpu/other", type_ok);
  t_true("info: subgroup_size > 0", i->subgroup_size > 0);
  t_true("info: max_storage_buffer_range > 0", i->max_storage_buffer_range > 0);
  t_true("info: max_workgroup_invocations > 0 and max_workgroup_count_x > 0",
         i->max_workgroup_invocations > 0 && i->max_workgroup_count_x > 0);
  t_true("info: precision is 32 or 64", i->precision == 32 || i->precision == 64);
  t_true("info: precision 64 only where the device has shaderFloat64",
         i->precision == 32 || i->float64);
  t_true("info: timestamp_period_ns >= 0", i->timestamp_period_ns >= 0);
}

/* Uploads random bytes at assorted (unaligned) offsets into a buffer, keeps
 * a host mirror, and checks full and partial downloads byte for byte. */
static void roundtrip(sessile_gpu *g, size_t bytes, sessile_buffer_kind kind, const char *kname) {
  char what[160];
  sessile_buffer *b = NULL;
  sessile_status s = sessile_buffer_create(g, bytes, kind, &b);
  t_ok("buffer_create", s);
  if (s != SESSILE_OK) return;
  t_true("buffer_size returns the size asked for", sessile_buffer_size(b) == bytes);
  if (kind == SESSILE_BUFFER_MAPPED)
    t_true("MAPPED buffer has a host pointer", sessile_buffer_host_ptr(b) != NULL);

  unsigned char *mirror = calloc(bytes, 1), *got = malloc(bytes), *src = malloc(bytes);
  if (!mirror || !got || !src) {
    printf("FAIL out of host memory\n");
    exit(1);
  }
  t_ok("download of a fresh buffer", sessile_buffer_download(b, 0, got, bytes));
  snprintf(what, sizeof what, "%s buffer of %zu bytes starts zeroed", kname, bytes);
  t_true(what, all_zero(got, bytes));

  /* (offset, length) pairs: start, unaligned middle, the very end, whole. */
  const size_t pieces[][2] = {{0, 1},           {1, 7},          {3, 4096 + 5},
                              {bytes / 2 + 1, bytes / 3},        {bytes - 9, 9},
                              {bytes - 1, 1},   {0, 0},          {bytes, 0}};
  int ok = 1;
  for (size_t k = 0; k < sizeof pieces / sizeof pieces[0]; k++) {
    size_t off = pieces[k][0], len = pieces[k][1];
    random_bytes(src, len, 1000 + k);
    s = sessile_buffer_upload(b, off, src, len);
    t_ok("buffer_upload in range", s);
    ok &= s == SESSILE_OK;
    memcpy(mirror + off, src, len);
  }
  t_ok("download whole buffer", sessile_buffer_download(b, 0, got, bytes));
  snprintf(what, sizeof what, "%s %zu bytes: 8 uploads at offsets, whole download == mirror",
           kname, bytes);
  t_true(what, ok && memcmp(got, mirror, bytes) == 0);
  /* Partial download at an odd offset. */
  memset(got, 0xAB, bytes);
  t_ok("partial download", sessile_buffer_download(b, 5, got, bytes - 12));
  snprintf(what, sizeof what, "%s: download of %zu bytes at offset 5 == mirror", kname,
           bytes - 12);
  t_true(what, memcmp(got, mirror + 5, bytes - 12) == 0);
  if (kind == SESSILE_BUFFER_MAPPED) {
    snprintf(what, sizeof what, "%s: host pointer sees the uploaded bytes", kname);
    t_true(what, memcmp(sessile_buffer_host_ptr(b), mirror, bytes) == 0);
  }

  /* Out-of-range transfers are usage errors and leave the buffer alone. */
  sessile_error_clear();
  s = sessile_buffer_upload(b, bytes - 3, src, 4);
  snprintf(what, sizeof what, "%s: upload of 4 bytes at size-3 -> %s (\"%s\")", kname,
           sessile_status_name(s), sessile_error_message());
  t_true(what, s == SESSILE_ERR_USAGE);
  s = sessile_buffer_upload(b, bytes + 1, src, 0);
  snprintf(what, sizeof what, "%s: upload at offset size+1 -> %s", kname, sessile_status_name(s));
  t_true(what, s == SESSILE_ERR_USAGE);
  s = sessile_buffer_upload(b, 8, src, SIZE_MAX - 4); /* offset + bytes wraps around */
  snprintf(what, sizeof what, "%s: upload whose offset+bytes overflows size_t -> %s", kname,
           sessile_status_name(s));
  t_true(what, s == SESSILE_ERR_USAGE);
  s = sessile_buffer_download(b, 1, got, bytes);
  snprintf(what, sizeof what, "%s: download of size bytes at offset 1 -> %s", kname,
           sessile_status_name(s));
  t_true(what, s == SESSILE_ERR_USAGE);
  t_ok("download after refused transfers", sessile_buffer_download(b, 0, got, bytes));
  snprintf(what, sizeof what, "%s: refused transfers changed nothing", kname);
  t_true(what, memcmp(got, mirror, bytes) == 0);

  sessile_buffer_destroy(b);
  free(mirror);
  free(got);
  free(src);
}

static void test_buffers(sessile_gpu *g) {
  printf("-- buffers\n");
  roundtrip(g, (1u << 20) + 13, SESSILE_BUFFER_DEVICE, "DEVICE");
  roundtrip(g, 4099 + 4096, SESSILE_BUFFER_MAPPED, "MAPPED");

  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  sessile_buffer *b = (sessile_buffer *)&b; /* must be reset to NULL on failure */
  sessile_error_clear();
  size_t too_big = (size_t)i->max_storage_buffer_range + 1;
  sessile_status s = sessile_buffer_create(g, too_big, SESSILE_BUFFER_DEVICE, &b);
  printf("   create of %zu bytes: %s: \"%s\"\n", too_big, sessile_status_name(s),
         sessile_error_message());
  t_true("buffer of maxStorageBufferRange+1 bytes -> SESSILE_ERR_TOO_LARGE, *out = NULL",
         s == SESSILE_ERR_TOO_LARGE && b == NULL);
  t_true("  ... and its message names maxStorageBufferRange",
         strstr(sessile_error_message(), "maxStorageBufferRange") != NULL);
  b = (sessile_buffer *)&b;
  s = sessile_buffer_create(g, too_big, SESSILE_BUFFER_MAPPED, &b);
  t_true("MAPPED buffer of maxStorageBufferRange+1 bytes -> SESSILE_ERR_TOO_LARGE",
         s == SESSILE_ERR_TOO_LARGE && b == NULL);

  b = (sessile_buffer *)&b;
  sessile_error_clear();
  s = sessile_buffer_create(g, 0, SESSILE_BUFFER_DEVICE, &b);
  printf("   create of 0 bytes: %s: \"%s\"\n", sessile_status_name(s), sessile_error_message());
  t_true("buffer of 0 bytes -> SESSILE_ERR_USAGE, *out = NULL, message set",
         s == SESSILE_ERR_USAGE && b == NULL && sessile_error_message()[0] != '\0');
}

static void test_kernels(sessile_gpu *g) {
  printf("-- kernels and the SPIR-V table\n");
  const sessile_spirv *sp = sessile_spirv_find("la/axpy.f64");
  t_true("spirv_find(\"la/axpy.f64\") is non-NULL, named, non-empty, SPIR-V magic",
         sp && sp->name && strcmp(sp->name, "la/axpy.f64") == 0 && sp->bytes >= 20 &&
             sp->bytes % 4 == 0 && sp->code && sp->code[0] == 0x07230203u);
  t_true("spirv_find(\"la/axpy.f32\") is non-NULL", sessile_spirv_find("la/axpy.f32") != NULL);
  t_true("spirv_find(\"nope\") is NULL", sessile_spirv_find("nope") == NULL);
  t_true("spirv_find(\"la/axpy\") (no precision suffix) is NULL",
         sessile_spirv_find("la/axpy") == NULL);

  sessile_kernel *k = (sessile_kernel *)&k;
  sessile_error_clear();
  sessile_kernel_decl bad = sessile_la_kernels[K_FILL];
  bad.name = "la/no-such-kernel";
  sessile_status s = sessile_kernel_create_decl(g, &bad, 8, 0, &k);
  printf("   kernel_create_decl(\"la/no-such-kernel\"): %s: \"%s\"\n", sessile_status_name(s),
         sessile_error_message());
  t_true("kernel_create with an unknown name fails, *out = NULL, message names the kernel",
         s != SESSILE_OK && k == NULL && strstr(sessile_error_message(), "no-such-kernel") != NULL);
}

/* A real dispatch through the public API: la/fill with no coefficient slot
 * writes 1 to the first n reals and 0 to the rest of the last REAL4
 * (shaders/common/vecpush.glsl); timestamps around it are ordered. */
static void test_dispatch(sessile_gpu *g) {
  printf("-- command recording: one dispatch and timestamps\n");
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  const int f64 = i->precision == 64;
  const uint32_t n = 1001, n4 = (n + 3) / 4, rb = f64 ? 8 : 4;
  sessile_kernel *k = NULL;
  sessile_cmd *c = NULL;
  sessile_buffer *scal = NULL, *y = NULL;
  sessile_status s = sessile_kernel_create_decl(g, &sessile_la_kernels[K_FILL], 0, 0, &k);
  t_ok("kernel_create_decl la/fill", s);
  if (s == SESSILE_OK) {
    uint32_t ls = sessile_kernel_local_size(k);
    printf("   la/fill local size %u\n", ls);
    t_true("kernel local size: default 256 clamped to maxComputeWorkGroupInvocations",
           ls == (i->max_workgroup_invocations < 256 ? i->max_workgroup_invocations : 256));
  }
  if (s == SESSILE_OK) s = sessile_buffer_create(g, 64 * rb, SESSILE_BUFFER_MAPPED, &scal);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, (size_t)(n4 + 1) * 4 * rb, SESSILE_BUFFER_DEVICE, &y);
  /* A marker past the vector the kernel must not touch. */
  unsigned char marker[32];
  memset(marker, 0x5A, sizeof marker);
  if (s == SESSILE_OK) s = sessile_buffer_upload(y, (size_t)n4 * 4 * rb, marker, 4 * rb);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &c);
  vec_push push = {.n4 = n4, .n = n, .a_slot = -1, .guard = -1};
  sessile_buffer *bufs[2] = {scal, y};
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_timestamp(c, 0);
  /* One group more than needed: the kernel must bounds-check against n4. */
  uint32_t ls = k ? sessile_kernel_local_size(k) : 1, groups = (n4 + ls - 1) / ls + 1;
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  if (s == SESSILE_OK) s = sessile_cmd_timestamp(c, 1);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c); /* re-submission of the same recording */
  t_ok("record, submit twice", s);
  if (s == SESSILE_OK) {
    size_t total = (size_t)(n4 + 1) * 4;
    double *v = malloc(total * sizeof *v);
    unsigned char *raw = malloc(total * rb);
    t_ok("download", sessile_buffer_download(y, 0, raw, total * rb));
    for (size_t e = 0; e < (size_t)n4 * 4; e++) {
      if (f64) memcpy(&v[e], raw + e * 8, 8);
      else {
        float f;
        memcpy(&f, raw + e * 4, 4);
        v[e] = f;
      }
    }
    int ok = 1;
    for (size_t e = 0; e < (size_t)n4 * 4; e++) ok &= v[e] == (e < n ? 1.0 : 0.0);
    t_true("la/fill dispatch: y[0..1000] == 1 exactly, padding y[1001..1003] == 0", ok);
    t_true("la/fill dispatch: bytes past the vector untouched",
           memcmp(raw + (size_t)n4 * 4 * rb, marker, 4 * rb) == 0);
    free(v);
    free(raw);
    double ns = -1;
    sessile_status ts = sessile_cmd_elapsed_ns(c, 0, 1, &ns);
    if (i->timestamp_period_ns > 0) {
      printf("   elapsed between timestamps: %.0f ns\n", ns);
      t_true("cmd_elapsed_ns(0, 1) succeeds and is >= 0", ts == SESSILE_OK && ns >= 0);
      ts = sessile_cmd_elapsed_ns(c, 0, 2, &ns);
      t_true("cmd_elapsed_ns with an unrecorded slot fails", ts != SESSILE_OK);
    } else {
      t_true("no timestamps on this device: elapsed_ns -> SESSILE_ERR_UNSUPPORTED",
             ts == SESSILE_ERR_UNSUPPORTED);
    }
    s = sessile_cmd_timestamp(c, 64);
    t_true("cmd_timestamp slot 64 (of 0..63) fails", s != SESSILE_OK);
  }
  sessile_cmd_destroy(c);
  sessile_buffer_destroy(y);
  sessile_buffer_destroy(scal);
  sessile_kernel_destroy(k);
}

/* Every one of the n reals (rb bytes each) in raw is 1. */
static int all_one(const unsigned char *raw, size_t n, uint32_t rb) {
  for (size_t e = 0; e < n; e++) {
    double v;
    if (rb == 8) memcpy(&v, raw + 8 * e, 8);
    else {
      float f;
      memcpy(&f, raw + 4 * e, 4);
      v = f;
    }
    if (v != 1.0) return 0;
  }
  return 1;
}

/* sessile_cmd_indirect: dispatches of the counts it was given read them from
 * its buffer; a kernel that zeroes them (la/fill of 0 over that buffer,
 * itself of another count, so dispatched directly) skips every later
 * dispatch of those counts, which then leave their vector untouched; a new
 * recording uploads the counts again; asked after a dispatch it fails. */
static void test_indirect(sessile_gpu *g) {
  printf("-- indirect dispatch: counts that a kernel zeroes skip the dispatches after it\n");
  const uint32_t rb = sessile_gpu_info_of(g)->precision == 64 ? 8 : 4;
  sessile_kernel *k = NULL;
  sessile_cmd *c = NULL;
  sessile_buffer *scal = NULL, *args = NULL, *y1 = NULL, *y2 = NULL;
  sessile_status s = sessile_kernel_create_decl(g, &sessile_la_kernels[K_FILL], 0, 0, &k);
  uint32_t ls = k ? sessile_kernel_local_size(k) : 1, g1 = 3, g2 = 5;
  size_t n1 = 4 * (size_t)ls * g1, n2 = 4 * (size_t)ls * g2, nargs = (4 + 3 * SESSILE_INDIRECT_MAX) * 4 / rb;
  unsigned char zero[64] = {0}, *mark = malloc(n2 * rb), *raw = malloc(n2 * rb);
  memset(mark, 0x5A, n2 * rb);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, 64 * rb, SESSILE_BUFFER_MAPPED, &scal);
  if (s == SESSILE_OK) s = sessile_buffer_upload(scal, 0, zero, rb); /* s[0] = 0 */
  /* la/fill writes whole REAL4s: the counts' buffer padded to them (without,
   * its last invocation wrote past the end: GPU-assisted validation) */
  if (s == SESSILE_OK) s = sessile_buffer_create(g, (nargs + 3) / 4 * 4 * rb, SESSILE_BUFFER_DEVICE, &args);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, n1 * rb, SESSILE_BUFFER_DEVICE, &y1);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, n2 * rb, SESSILE_BUFFER_DEVICE, &y2);
  if (s == SESSILE_OK) s = sessile_buffer_upload(y1, 0, mark, n1 * rb);
  if (s == SESSILE_OK) s = sessile_buffer_upload(y2, 0, mark, n2 * rb);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &c);
  vec_push p1 = {.n4 = (uint32_t)n1 / 4, .n = (uint32_t)n1, .a_slot = -1, .guard = -1};
  vec_push p2 = {.n4 = (uint32_t)n2 / 4, .n = (uint32_t)n2, .a_slot = -1, .guard = -1};
  vec_push pz = {.n4 = (uint32_t)(nargs + 3) / 4, .n = (uint32_t)nargs, .a_slot = 0, .guard = -1};
  sessile_buffer *b1[2] = {scal, y1}, *b2[2] = {scal, y2}, *bz[2] = {scal, args};
  const uint32_t counts[2] = {g1, g2};
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_indirect(c, args, counts, 2);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, g1, b1, &p1);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, (pz.n4 + ls - 1) / ls, bz, &pz); /* zeroes the counts */
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, g2, b2, &p2);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  t_ok("three dispatches, two of them indirect", s);
  int ok2 = 0;
  if (s == SESSILE_OK) s = sessile_buffer_download(y1, 0, raw, n1 * rb);
  t_true("the indirect dispatch before the zeroing ran: y1 == 1 everywhere", s == SESSILE_OK && all_one(raw, n1, rb));
  if (s == SESSILE_OK) s = sessile_buffer_download(y2, 0, raw, n2 * rb);
  ok2 = s == SESSILE_OK && memcmp(raw, mark, n2 * rb) == 0;
  t_true("the one after it launched nothing: y2 untouched", ok2);
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_indirect(c, args, counts, 2);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, g2, b2, &p2);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  if (s == SESSILE_OK) s = sessile_buffer_download(y2, 0, raw, n2 * rb);
  t_true("a new recording uploads the counts again: y2 filled", s == SESSILE_OK && memcmp(raw, mark, n2 * rb) != 0);
  sessile_status late = SESSILE_OK;
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, g1, b1, &p1);
  if (s == SESSILE_OK) late = sessile_cmd_indirect(c, args, counts, 2);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  t_true("sessile_cmd_indirect after a dispatch is refused", s == SESSILE_OK && late == SESSILE_ERR_INTERNAL);
  free(mark), free(raw);
  sessile_cmd_destroy(c);
  sessile_buffer_destroy(y1), sessile_buffer_destroy(y2), sessile_buffer_destroy(args), sessile_buffer_destroy(scal);
  sessile_kernel_destroy(k);
}

/* sessile_cmd_copy between dispatches: fill y1 with 1, copy y1 into y2, then
 * la/copy reads y2 into y3: the copy sees the fill's writes and the dispatch
 * after it sees the copy's (y3 == 1 everywhere, y2 and y3 were marked); a
 * copy larger than its buffers, or after a download, is refused. */
static void test_copy(sessile_gpu *g) {
  printf("-- sessile_cmd_copy: a buffer copy between two dispatches of a recording\n");
  const uint32_t rb = sessile_gpu_info_of(g)->precision == 64 ? 8 : 4;
  sessile_kernel *kf = NULL, *kc = NULL;
  sessile_cmd *c = NULL;
  sessile_buffer *scal = NULL, *y1 = NULL, *y2 = NULL, *y3 = NULL;
  sessile_status s = sessile_kernel_create_decl(g, &sessile_la_kernels[K_FILL], 0, 0, &kf);
  if (s == SESSILE_OK) s = sessile_kernel_create_decl(g, &sessile_la_kernels[K_COPY], 0, 0, &kc);
  uint32_t ls = kf ? sessile_kernel_local_size(kf) : 1, groups = 3;
  size_t n = 4 * (size_t)ls * groups;
  unsigned char zero[64] = {0}, *mark = malloc(n * rb), *raw = malloc(n * rb);
  memset(mark, 0x5A, n * rb);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, 64 * rb, SESSILE_BUFFER_MAPPED, &scal);
  if (s == SESSILE_OK) s = sessile_buffer_upload(scal, 0, zero, rb);
  sessile_buffer **ys[3] = {&y1, &y2, &y3};
  for (int i = 0; i < 3 && s == SESSILE_OK; i++) s = sessile_buffer_create(g, n * rb, SESSILE_BUFFER_DEVICE, ys[i]);
  for (int i = 0; i < 3 && s == SESSILE_OK; i++) s = sessile_buffer_upload(*ys[i], 0, mark, n * rb);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &c);
  vec_push p = {.n4 = (uint32_t)n / 4, .n = (uint32_t)n, .a_slot = -1, .guard = -1};
  sessile_buffer *bf[2] = {scal, y1}, *bc[3] = {scal, y2, y3};
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, kf, groups, bf, &p);
  if (s == SESSILE_OK) s = sessile_cmd_copy(c, y1, y2, n * rb);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, kc, groups, bc, &p);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  t_ok("fill, copy, copy kernel in one recording", s);
  if (s == SESSILE_OK) s = sessile_buffer_download(y3, 0, raw, n * rb);
  t_true("y3 == 1 everywhere: the copy saw the fill, the kernel after it saw the copy",
         s == SESSILE_OK && all_one(raw, n, rb));
  sessile_status big = SESSILE_OK, late = SESSILE_OK;
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) big = sessile_cmd_copy(c, y1, y2, n * rb + 1);
  if (s == SESSILE_OK) s = sessile_cmd_download(c, y1, 0, raw, rb);
  if (s == SESSILE_OK) late = sessile_cmd_copy(c, y1, y2, rb);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  t_true("a copy past its buffers' end is refused", s == SESSILE_OK && big == SESSILE_ERR_INTERNAL);
  t_true("a copy after a recorded download is refused", s == SESSILE_OK && late == SESSILE_ERR_INTERNAL);
  free(mark), free(raw);
  sessile_cmd_destroy(c);
  sessile_buffer_destroy(y1), sessile_buffer_destroy(y2), sessile_buffer_destroy(y3), sessile_buffer_destroy(scal);
  sessile_kernel_destroy(kf), sessile_kernel_destroy(kc);
}

/* The kernel profile: SESSILE_PROFILE_MAX + 6 dispatches of la/fill in one
 * recording submitted twice give 2 x SESSILE_PROFILE_MAX timed calls of it
 * and 2 x 6 untimed dispatches, with a
 * positive device time; off, a submission adds nothing; on again clears. */
/* sessile_cmd_upload/download: two uploads, a scale, two downloads in one
 * submission; the bytes of the host's own product (2 a and 3 a are exact in
 * either precision: a holds floats); a re-submission replays the uploads; the
 * order is enforced.  Under SESSILE_STAGED=1 the device buffer is not mapped
 * and every transfer is a copy through the recording's staging buffer, which
 * runs out mid-recording and is replaced (1.6 MB of transfers against its
 * first 1 MiB). */
static void test_recorded_transfers(sessile_gpu *g) {
  printf("-- transfers inside a recording: uploads, a dispatch, downloads\n");
  const size_t n = 100003, n4 = (n + 3) / 4, half = n / 2;
  sessile_kernel *k = NULL;
  sessile_cmd *c = NULL;
  sessile_buffer *scal = NULL, *y = NULL;
  double *a = malloc(n * sizeof *a), *out = calloc(n, sizeof *out), tail[7] = {0};
  uint64_t z = 12345;
  for (size_t i = 0; i < n; i++) {
    z = z * 6364136223846793005ull + 1442695040888963407ull;
    a[i] = (double)(float)((double)(z >> 11) / 9007199254740992.0 - 0.5);
  }
  sessile_status e, s = sessile_kernel_create_decl(g, &sessile_la_kernels[K_SCALE], 0, 0, &k);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, 64 * 8, SESSILE_BUFFER_MAPPED, &scal);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, n4 * 4 * 8, SESSILE_BUFFER_DEVICE, &y);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &c);
  t_ok("scale kernel, buffers, recording", s);
  if (s != SESSILE_OK) goto done;
  printf("   y is %s\n", sessile_buffer_host_ptr(y) ? "mapped (direct copies)" : "not mapped (staged copies)");
  vec_push push = {.n4 = (uint32_t)n4, .n = (uint32_t)n, .a_slot = 0, .guard = -1};
  sessile_buffer *bufs[2] = {scal, y};
  uint32_t groups = (uint32_t)((n4 + sessile_kernel_local_size(k) - 1) / sessile_kernel_local_size(k));
  const double two = 2, three = 3;
  s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_upload_reals(c, scal, 0, &two, 1);
  if (s == SESSILE_OK) s = sessile_cmd_upload_reals(c, y, 0, a, half);
  if (s == SESSILE_OK) s = sessile_cmd_upload_reals(c, y, half, a + half, n - half);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  if (s == SESSILE_OK) s = sessile_cmd_download_reals(c, y, 0, out, n);
  if (s == SESSILE_OK) s = sessile_cmd_download_reals(c, y, n - 7, tail, 7);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  int ok_rec = s == SESSILE_OK;
  for (size_t i = 0; ok_rec && i < n; i++) ok_rec &= out[i] == 0;
  t_true("nothing is downloaded before the submission", ok_rec);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  t_ok("upload, upload, scale, download, download: one submission", s);
  int ok = s == SESSILE_OK;
  for (size_t i = 0; ok && i < n; i++) ok &= out[i] == 2 * a[i];
  for (size_t i = 0; ok && i < 7; i++) ok &= tail[i] == 2 * a[n - 7 + i];
  t_true("the downloads hold 2 a, every value exact (and the 7 at an offset)", ok);
  e = s == SESSILE_OK ? sessile_cmd_submit_wait(c) : s;
  t_true("a recording with uploads is not submitted twice (SESSILE_ERR_INTERNAL)", e == SESSILE_ERR_INTERNAL);
  /* without uploads, a re-submission writes the downloads again */
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  if (s == SESSILE_OK) s = sessile_cmd_download_reals(c, y, 0, out, n);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  memset(out, 0, n * sizeof *out);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  ok = s == SESSILE_OK;
  for (size_t i = 0; ok && i < n; i++) ok &= out[i] == 8 * a[i];
  t_true("a recording without uploads submitted twice: 4 a, then 8 a downloaded again", ok);
  /* a mapped buffer's upload is written when the call is made */
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_upload_reals(c, scal, 0, &three, 1);
  if (s == SESSILE_OK) s = sessile_cmd_upload_reals(c, y, 0, a, n);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  if (s == SESSILE_OK) s = sessile_cmd_download_reals(c, y, 0, out, n);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  ok = s == SESSILE_OK;
  for (size_t i = 0; ok && i < n; i++) ok &= out[i] == 3 * a[i];
  t_true("a second recording on the same command: 3 a", ok);
  /* the order: uploads first, downloads last */
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  e = s == SESSILE_OK ? sessile_cmd_upload_reals(c, y, 0, a, 4) : s;
  printf("   upload after a dispatch: %s: \"%s\"\n", sessile_status_name(e), sessile_error_message());
  t_true("an upload after a dispatch fails (SESSILE_ERR_INTERNAL)", e == SESSILE_ERR_INTERNAL);
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_download_reals(c, y, 0, out, 4);
  e = s == SESSILE_OK ? sessile_cmd_dispatch(c, k, groups, bufs, &push) : s;
  printf("   dispatch after a download: %s: \"%s\"\n", sessile_status_name(e), sessile_error_message());
  t_true("a dispatch after a download fails (SESSILE_ERR_INTERNAL)", e == SESSILE_ERR_INTERNAL);
  e = s == SESSILE_OK ? sessile_cmd_download_reals(c, y, n4 * 4 - 2, out, 4) : s;
  t_true("a download past the buffer's end fails (SESSILE_ERR_USAGE)", e == SESSILE_ERR_USAGE);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  e = sessile_cmd_upload(c, y, 0, a, 8);
  t_true("an upload outside a recording fails (SESSILE_ERR_INTERNAL)", e == SESSILE_ERR_INTERNAL);
  t_ok("the recordings end cleanly", s);
done:
  sessile_cmd_destroy(c);
  sessile_buffer_destroy(y);
  sessile_buffer_destroy(scal);
  sessile_kernel_destroy(k);
  free(a), free(out);
}

static void test_profile(sessile_gpu *g) {
  printf("-- kernel profile (sessile_gpu_profile)\n");
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  if (!(i->timestamp_period_ns > 0)) {
    t_true("no timestamps on this device: profile on -> SESSILE_ERR_UNSUPPORTED",
           sessile_gpu_profile(g, 1) == SESSILE_ERR_UNSUPPORTED);
    return;
  }
  const uint32_t n = 1001, n4 = (n + 3) / 4, rb = i->precision == 64 ? 8 : 4;
  sessile_kernel *k = NULL;
  sessile_cmd *c = NULL;
  sessile_buffer *scal = NULL, *y = NULL;
  sessile_status s = sessile_kernel_create_decl(g, &sessile_la_kernels[K_FILL], 0, 0, &k);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, 64 * rb, SESSILE_BUFFER_MAPPED, &scal);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, (size_t)(n4 + 1) * 4 * rb, SESSILE_BUFFER_DEVICE, &y);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &c);
  if (s == SESSILE_OK) s = sessile_gpu_profile(g, 1);
  vec_push push = {.n4 = n4, .n = n, .a_slot = -1, .guard = -1};
  sessile_buffer *bufs[2] = {scal, y};
  uint32_t groups = k ? (n4 + sessile_kernel_local_size(k) - 1) / sessile_kernel_local_size(k) : 1;
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  for (int d = 0; d < SESSILE_PROFILE_MAX + 6 && s == SESSILE_OK; d++) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  t_ok("profile on, SESSILE_PROFILE_MAX + 6 dispatches recorded, submitted twice", s);
  const sessile_kernel_time *t = NULL;
  uint64_t untimed = 0;
  size_t nt = sessile_gpu_profile_read(g, &t, &untimed);
  if (nt == 1) printf("   %s: %llu calls, %.4f ms, %llu untimed\n", t[0].name, (unsigned long long)t[0].calls, t[0].ms,
                      (unsigned long long)untimed);
  t_true("one kernel, la/fill, 2 x SESSILE_PROFILE_MAX timed calls, 12 untimed dispatches, device time > 0",
         nt == 1 && strncmp(t[0].name, "la/fill", 7) == 0 && t[0].calls == 2 * SESSILE_PROFILE_MAX && untimed == 12 &&
             t[0].ms > 0);
  double ms = nt == 1 ? t[0].ms : -1;
  if (s == SESSILE_OK) s = sessile_gpu_profile(g, 0);
  if (s == SESSILE_OK) s = sessile_cmd_begin(c);
  if (s == SESSILE_OK) s = sessile_cmd_dispatch(c, k, groups, bufs, &push);
  if (s == SESSILE_OK) s = sessile_cmd_end(c);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(c);
  nt = sessile_gpu_profile_read(g, &t, &untimed);
  t_true("profile off: a further submission adds nothing",
         s == SESSILE_OK && nt == 1 && t[0].calls == 2 * SESSILE_PROFILE_MAX && t[0].ms == ms && untimed == 12);
  if (s == SESSILE_OK) s = sessile_gpu_profile(g, 1);
  t_true("profile on again clears the table", s == SESSILE_OK && sessile_gpu_profile_read(g, NULL, NULL) == 0);
  sessile_gpu_profile(g, 0);
  sessile_cmd_destroy(c);
  sessile_buffer_destroy(y);
  sessile_buffer_destroy(scal);
  sessile_kernel_destroy(k);
}

static void test_device_choice(void) {
  printf("-- device choice\n");
  sessile_gpu_options o;
  sessile_gpu_options_default(&o);
  t_true("options_default: device NULL, validation -1, precision 0, cache_dir NULL, validation_message NULL",
         o.device == NULL && o.validation == -1 && o.precision == 0 && o.cache_dir == NULL &&
             o.validation_message == NULL);
  o.validation = 1;
  o.device = "no-such-device";
  sessile_gpu *g = (sessile_gpu *)&g;
  sessile_error_clear();
  sessile_status s = sessile_gpu_create(&o, &g);
  printf("   device \"no-such-device\": %s: \"%s\"\n", sessile_status_name(s),
         sessile_error_message());
  /* A device choice that names nothing is bad user input (docs/design.md). */
  t_true("device \"no-such-device\" -> SESSILE_ERR_USAGE, *out = NULL",
         s == SESSILE_ERR_USAGE && g == NULL);
  t_true("  ... and the message points to `sessile devices`",
         strstr(sessile_error_message(), "sessile devices") != NULL);

  o.device = "9999";
  g = (sessile_gpu *)&g;
  s = sessile_gpu_create(&o, &g);
  printf("   device \"9999\": %s: \"%s\"\n", sessile_status_name(s), sessile_error_message());
  t_true("device index 9999 -> SESSILE_ERR_USAGE", s == SESSILE_ERR_USAGE && g == NULL);

  o.device = "0";
  g = NULL;
  s = sessile_gpu_create(&o, &g);
  t_ok("device \"0\"", s);
  t_true("device \"0\" works and is device index 0",
         s == SESSILE_OK && g && sessile_gpu_info_of(g)->index == 0);
  if (g) {
    uint64_t v = sessile_gpu_validation_count(g);
    t_check("device \"0\": validation messages", (double)v, 0);
    sessile_gpu_destroy(g);
  }

  o.device = NULL;
  o.precision = 48;
  g = (sessile_gpu *)&g;
  s = sessile_gpu_create(&o, &g);
  t_true("precision 48 -> SESSILE_ERR_USAGE", s == SESSILE_ERR_USAGE && g == NULL);
}

static void test_destroy_null(void) {
  printf("-- destroy(NULL)\n");
  sessile_gpu_destroy(NULL);
  sessile_buffer_destroy(NULL);
  sessile_kernel_destroy(NULL);
  sessile_cmd_destroy(NULL);
  sessile_la_destroy(NULL);
  sessile_vec_destroy(NULL);
  sessile_mat_destroy(NULL);
  t_true("gpu/buffer/kernel/cmd/la/vec/mat destroy(NULL) are no-ops", 1);
}

/* A validation message goes to sessile_gpu_options.validation_message (and is
 * counted), not to stderr: a deliberately invalid vkCreateBuffer (size 0) on
 * a second context, so the test's own context stays clean. */
typedef struct { int n, errors; } vmsgs;
static void on_validation(void *user, int is_error, const char *message) {
  vmsgs *v = user;
  v->n++;
  v->errors += is_error;
  printf("   (callback) validation %s: %.120s...\n", is_error ? "error" : "warning", message);
}

static void test_validation_callback(void) {
  printf("-- validation messages through the callback\n");
  sessile_gpu_options o;
  sessile_gpu_options_default(&o);
  o.validation = 1;
  vmsgs got = {0, 0};
  o.validation_message = on_validation;
  o.validation_user = &got;
  sessile_gpu *g = NULL;
  sessile_status s = sessile_gpu_create(&o, &g);
  t_ok("context with a validation callback", s);
  if (s != SESSILE_OK) return;
  fflush(stderr);
  char path[] = "/tmp/sessile-stderr-XXXXXX";
  int fd = mkstemp(path), saved = dup(2);
  dup2(fd, 2);
  VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                           .size = 0, /* invalid: size must be greater than 0 */
                           .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  VkBuffer b = VK_NULL_HANDLE;
  VkResult r = vkCreateBuffer(g->device, &ci, NULL, &b);
  if (r == VK_SUCCESS && b) vkDestroyBuffer(g->device, b, NULL);
  fflush(stderr);
  dup2(saved, 2);
  close(saved);
  long bytes = (long)lseek(fd, 0, SEEK_END);
  close(fd);
  unlink(path);
  t_true("the invalid call reached the callback as an error", got.errors >= 1);
  t_true("the count includes it", sessile_gpu_validation_count(g) == (uint64_t)got.n && got.n >= 1);
  t_check("bytes written to stderr meanwhile", (double)bytes, 0);
  sessile_gpu_destroy(g);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  test_info(g);
  test_buffers(g);
  test_kernels(g);
  test_dispatch(g);
  test_indirect(g);
  test_copy(g);
  test_recorded_transfers(g);
  test_profile(g);
  test_device_choice();
  test_validation_callback();
  test_destroy_null();
  return t_finish(g);
}
