/* GPU vectors: n reals padded with zeros to a multiple of 4 (REAL4 loads),
 * and the immediate (record, submit, wait) vector operations. */
#include <stdlib.h>
#include "la_internal.h"

sessile_status sessile_vec_create(sessile_la *la, uint32_t n, sessile_vec **out) {
  *out = NULL;
  SESSILE_CHECK(n > 0, SESSILE_ERR_USAGE, "a vector of length 0 was asked for");
  sessile_vec *v = calloc(1, sizeof *v);
  SESSILE_CHECK(v, SESSILE_ERR_NO_MEMORY, "out of host memory");
  v->la = la;
  v->n = n;
  v->n4 = (n + 3) / 4;
  v->serial = ++la->vec_serial;
  sessile_status s = sessile_buffer_create(la->gpu, (size_t)v->n4 * 4 * la->real_bytes,
                                           SESSILE_BUFFER_DEVICE, &v->buf);
  if (s != SESSILE_OK) {
    free(v);
    return s;
  }
  *out = v;
  return SESSILE_OK;
}

void sessile_vec_destroy(sessile_vec *v) {
  if (!v) return;
  sessile_buffer_destroy(v->buf);
  free(v);
}

uint32_t sessile_vec_size(const sessile_vec *v) { return v->n; }

sessile_status sessile_vec_upload(sessile_vec *v, const double *src) {
  return sessile_buffer_upload_reals(v->buf, 0, src, v->n);
}
sessile_status sessile_vec_download(sessile_vec *v, double *dst) {
  return sessile_buffer_download_reals(v->buf, 0, dst, v->n);
}

static sessile_status check_sizes(const sessile_vec *a, const sessile_vec *b, const char *op) {
  SESSILE_CHECK(a->n == b->n, SESSILE_ERR_USAGE, "%s: vector lengths differ (%u vs %u)", op, a->n,
                b->n);
  return SESSILE_OK;
}

/* Records one element-wise op with an immediate coefficient and runs it. */
static sessile_status run_vec(sessile_la *la, la_kernel_id id, double alpha, const sessile_vec *a,
                              const sessile_vec *b, const sessile_vec *w) {
  la_scalar_set(la, S_IMM, alpha);
  vref none = {NULL, 0};
  vref ra = vref_of(a), rb = b ? vref_of(b) : none, rw = w ? vref_of(w) : none;
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(rec_vec(la, la->cmd, id, a->n, ra, rb, rw, S_IMM, 0, -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}

sessile_status sessile_vec_fill(sessile_la *la, double value, sessile_vec *y) {
  return run_vec(la, K_FILL, value, y, NULL, NULL);
}
sessile_status sessile_vec_copy(sessile_la *la, const sessile_vec *x, sessile_vec *y) {
  SESSILE_CALL(check_sizes(x, y, "copy"));
  return run_vec(la, K_COPY, 1.0, x, y, NULL);
}
sessile_status sessile_vec_scale(sessile_la *la, double alpha, sessile_vec *y) {
  return run_vec(la, K_SCALE, alpha, y, NULL, NULL);
}
sessile_status sessile_vec_axpy(sessile_la *la, double alpha, const sessile_vec *x, sessile_vec *y) {
  SESSILE_CALL(check_sizes(x, y, "axpy"));
  return run_vec(la, K_AXPY, alpha, x, y, NULL);
}
sessile_status sessile_vec_aypx(sessile_la *la, double alpha, const sessile_vec *x, sessile_vec *y) {
  SESSILE_CALL(check_sizes(x, y, "aypx"));
  return run_vec(la, K_AYPX, alpha, x, y, NULL);
}
sessile_status sessile_vec_waxpy(sessile_la *la, double alpha, const sessile_vec *x,
                                 const sessile_vec *y, sessile_vec *w) {
  SESSILE_CALL(check_sizes(x, y, "waxpy"));
  SESSILE_CALL(check_sizes(x, w, "waxpy"));
  return run_vec(la, K_WAXPY, alpha, x, y, w);
}
sessile_status sessile_vec_pmul(sessile_la *la, const sessile_vec *x, const sessile_vec *y,
                                sessile_vec *w) {
  SESSILE_CALL(check_sizes(x, y, "pmul"));
  SESSILE_CALL(check_sizes(x, w, "pmul"));
  return run_vec(la, K_PMUL, 1.0, x, y, w);
}

static sessile_status run_dot(sessile_la *la, const sessile_vec *x, const sessile_vec *y, int sq,
                              double *out) {
  SESSILE_CALL(check_sizes(x, y, "dot"));
  uint32_t count;
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(rec_dot(la, la->cmd, x->n, vref_of(x), vref_of(y), 0, -1, &count));
  SESSILE_CALL(rec_reduce(la, la->cmd, count, 0, 1, S_IMM + 1, sq, -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(la->cmd));
  *out = la_scalar_read(la, S_IMM + 1);
  return SESSILE_OK;
}

sessile_status sessile_vec_dot(sessile_la *la, const sessile_vec *x, const sessile_vec *y,
                               double *out) {
  return run_dot(la, x, y, 0, out);
}
sessile_status sessile_vec_nrm2(sessile_la *la, const sessile_vec *x, double *out) {
  return run_dot(la, x, x, 1, out);
}

sessile_status la_ones(sessile_la *la, uint32_t n, sessile_vec **out) {
  SESSILE_CALL(sessile_vec_create(la, n, out));
  sessile_status s = sessile_vec_fill(la, 1.0, *out);
  if (s != SESSILE_OK) {
    sessile_vec_destroy(*out);
    *out = NULL;
  }
  return s;
}
