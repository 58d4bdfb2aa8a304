/* The SDS loop's checkpoint (sds_checkpoint.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_checkpoint.h"

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 0x100000001b3ull;
  return h;
}

uint64_t sds_ckpt_key(const char *model_text, uint64_t seed, double t_end, int frames, uint32_t max_cells) {
  uint64_t h = fnv(0xcbf29ce484222325ull, model_text, strlen(model_text));
  int64_t f = frames;
  h = fnv(h, &seed, sizeof seed), h = fnv(h, &t_end, sizeof t_end);
  h = fnv(h, &f, sizeof f), h = fnv(h, &max_cells, sizeof max_cells);
  return h;
}

uint64_t sds_ckpt_key_params(uint64_t key, const sessile_sds_run_params *own, const sessile_sds_run_params *p) {
  const sessile_param_table *t = &sessile_sds_run_param_table;
  for (int i = 0; i < t->count; i++) {
    double a = sessile_params_value(t, own, i), b = sessile_params_value(t, p, i);
    if (memcmp(&a, &b, sizeof a) == 0) continue;
    key = fnv(key, t->params[i].name, strlen(t->params[i].name) + 1);
    key = fnv(key, &b, sizeof b);
  }
  return key;
}

/* The organism's sizes, then one section per array (name, where, bytes). */
enum { NSEC = 21 };
_Static_assert(NSEC + 4 == SDS_CKPT_NSECTIONS, "sds_checkpoint.h");
typedef struct counts {
  uint64_t ncells, ntets, nedges, nfaces, nmorph, nstate;
} counts;
_Static_assert(sizeof(counts) == 6 * sizeof(uint64_t), "sds_ckpt_sections' counts_store");

static void layout(const sessile_sds *o, const counts *c, sessile_ckpt_section *s, void **dst[NSEC]) {
  size_t n = c->ncells, t = c->ntets, e = c->nedges, f = c->nfaces, d = sizeof(double), u = sizeof(uint32_t);
  const sessile_ckpt_section sec[NSEC] = {
      {"x", o->x, 3 * n * d},           {"v", o->v, 3 * n * d},
      {"r", o->r, n * d},               {"m", o->m, n * d},
      {"phi", o->phi, n * c->nmorph * d}, {"state", o->state, n * c->nstate * d},
      {"attract", o->attract, n * sizeof(int32_t)}, {"surface", o->surface, n},
      {"tet", o->tet, 4 * t * u},       {"tet_sm", o->tet_sm, t * d},
      {"tet_surface", o->tet_surface, t}, {"edge", o->edge, 2 * e * u},
      {"edge_sm", o->edge_sm, e * d},   {"edge_k", o->edge_k, e * d},
      {"edge_surface", o->edge_surface, e},
      {"face", o->face, 3 * f * u},     {"cell_edge_off", o->cell_edge_off, (n + 1) * u},
      {"cell_edge", o->cell_edge, 2 * e * u}, {"cell_tet_off", o->cell_tet_off, (n + 1) * u},
      {"cell_tet", o->cell_tet, 4 * t * u}, {NULL, NULL, 0}};
  memcpy(s, sec, sizeof sec);
  if (dst) {
    sessile_sds *w = (sessile_sds *)o;
    void **p[NSEC] = {(void **)&w->x,           (void **)&w->v,           (void **)&w->r,
                      (void **)&w->m,           (void **)&w->phi,         (void **)&w->state,
                      (void **)&w->attract,     (void **)&w->surface,     (void **)&w->tet,
                      (void **)&w->tet_sm,      (void **)&w->tet_surface, (void **)&w->edge,
                      (void **)&w->edge_sm,     (void **)&w->edge_k,      (void **)&w->edge_surface,
                      (void **)&w->face,
                      (void **)&w->cell_edge_off, (void **)&w->cell_edge, (void **)&w->cell_tet_off,
                      (void **)&w->cell_tet,    NULL};
    memcpy(dst, p, sizeof p);
  }
}

int sds_ckpt_sections(const sessile_sds *o, const sds_ckpt_loop *l, const double *retry_at, const uint64_t *sliver,
                      const double *frame_times, uint64_t counts_store[6], sessile_ckpt_section *s) {
  counts c = {o->ncells, o->ntets, o->nedges, o->nfaces, o->nmorph, o->nstate};
  memcpy(counts_store, &c, sizeof c);
  layout(o, &c, s, NULL);
  s[NSEC - 1] = (sessile_ckpt_section){"sds_counts", counts_store, sizeof c};
  s[NSEC] = (sessile_ckpt_section){"sds_loop", l, sizeof *l};
  s[NSEC + 1] = (sessile_ckpt_section){"retry_at", retry_at, l->retry_cap * sizeof(double)};
  s[NSEC + 2] = (sessile_ckpt_section){"slivers", sliver, 3 * l->nsliver * sizeof(uint64_t)};
  s[NSEC + 3] = (sessile_ckpt_section){"frame_times", frame_times, (size_t)l->frame * sizeof(double)};
  return NSEC + 4;
}

static sessile_status damaged(const char *what) {
  return sessile_error_set(SESSILE_ERR_IO, "the checkpoint's %s section is missing or does not fit (damaged?)", what);
}

sessile_status sds_ckpt_read(const sessile_ckpt *ck, uint64_t want_key, uint32_t nmorph, uint32_t nstate,
                             sessile_sds *o, sds_ckpt_loop *l, double **retry_at, uint64_t **sliver) {
  *retry_at = NULL, *sliver = NULL;
  size_t n = 0;
  const void *p = sessile_ckpt_get(ck, "sds_loop", &n);
  if (!p || n < sizeof l->version) return damaged("sds_loop");
  uint64_t version; /* first, so that another version's layout is named as such */
  memcpy(&version, p, sizeof version);
  SESSILE_CHECK(version == SDS_CKPT_VERSION, SESSILE_ERR_USAGE,
                "the checkpoint is of SDS checkpoint version %llu, this sessile reads version %u",
                (unsigned long long)version, SDS_CKPT_VERSION);
  if (n != sizeof *l) return damaged("sds_loop");
  memcpy(l, p, n);
  SESSILE_CHECK(l->key == want_key, SESSILE_ERR_USAGE,
                "the checkpoint was written by another model or configuration (seed, t_end, frames, "
                "max-cells) than the run's manifest names: it cannot be resumed");
  counts c;
  p = sessile_ckpt_get(ck, "sds_counts", &n);
  if (!p || n != sizeof c) return damaged("sds_counts");
  memcpy(&c, p, n);
  if (c.nmorph != nmorph || c.nstate != nstate || c.ncells < 4 || c.ncells > UINT32_MAX / 4 || c.ntets < 1 ||
      c.ntets > UINT32_MAX / 8 || c.nedges > UINT32_MAX / 4 || c.nfaces > UINT32_MAX / 4)
    return damaged("sds_counts");
  SESSILE_CALL(sessile_sds_alloc(o, (uint32_t)c.ncells, (uint32_t)c.ntets, nmorph, nstate));
  sessile_ckpt_section s[NSEC];
  void **dst[NSEC];
  /* allocate the derived arrays (alloc leaves them empty) to read into */
  size_t nn = c.ncells, t = c.ntets, e = c.nedges, f = c.nfaces;
  o->surface = malloc(nn ? nn : 1), o->tet_surface = malloc(t), o->edge = malloc((2 * e + 1) * 4);
  o->edge_sm = malloc((e + 1) * sizeof(double)), o->edge_k = malloc((e + 1) * sizeof(double));
  o->edge_surface = malloc(e + 1), o->face = malloc((3 * f + 1) * 4);
  o->cell_edge_off = malloc((nn + 1) * 4), o->cell_edge = malloc((2 * e + 1) * 4);
  o->cell_tet_off = malloc((nn + 1) * 4), o->cell_tet = malloc(4 * t * 4);
  o->nedges = (uint32_t)e, o->nfaces = (uint32_t)f;
  sessile_status st = SESSILE_OK;
  if (!o->surface || !o->tet_surface || !o->edge || !o->edge_sm || !o->edge_k || !o->edge_surface || !o->face ||
      !o->cell_edge_off || !o->cell_edge || !o->cell_tet_off || !o->cell_tet)
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the checkpoint's %llu cells",
                           (unsigned long long)c.ncells);
  layout(o, &c, s, dst);
  for (int i = 0; st == SESSILE_OK && s[i].name; i++) {
    p = sessile_ckpt_get(ck, s[i].name, &n);
    if (!p || n != s[i].bytes) st = damaged(s[i].name);
    else if (n) memcpy(*dst[i], p, n);
  }
  /* the indices must stay inside the arrays they name */
  for (size_t k = 0; st == SESSILE_OK && k < 4 * t; k++)
    if (o->tet[k] >= nn || o->cell_tet[k] >= t) st = damaged("tet");
  for (size_t k = 0; st == SESSILE_OK && k < 2 * e; k++)
    if (o->edge[k] >= nn || o->cell_edge[k] >= e) st = damaged("edge");
  for (size_t k = 0; st == SESSILE_OK && k < 3 * f; k++)
    if (o->face[k] >= nn) st = damaged("face");
  for (size_t k = 0; st == SESSILE_OK && k < e; k++)
    if (!(o->edge_k[k] > 0 && o->edge_k[k] < INFINITY)) st = damaged("edge_k");
  for (size_t k = 0; st == SESSILE_OK && k <= nn; k++)
    if (o->cell_edge_off[k] > 2 * e || o->cell_tet_off[k] > 4 * t || (k && (o->cell_edge_off[k] < o->cell_edge_off[k - 1] ||
                                                                            o->cell_tet_off[k] < o->cell_tet_off[k - 1])))
      st = damaged("incidence");
  if (st == SESSILE_OK) {
    p = sessile_ckpt_get(ck, "retry_at", &n);
    if (!p || l->retry_cap > UINT32_MAX || n != l->retry_cap * sizeof(double)) st = damaged("retry_at");
    else if (!(*retry_at = malloc(n ? n : 1))) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    else if (n) memcpy(*retry_at, p, n);
  }
  if (st == SESSILE_OK) {
    p = sessile_ckpt_get(ck, "slivers", &n);
    if (!p || l->nsliver > 4 * t || n != 3 * l->nsliver * sizeof(uint64_t)) st = damaged("slivers");
    else if (!(*sliver = malloc(n ? n : 1))) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    else if (n) memcpy(*sliver, p, n);
  }
  if (st != SESSILE_OK) {
    sessile_sds_free(o);
    free(*retry_at), free(*sliver);
    *retry_at = NULL, *sliver = NULL;
  }
  return st;
}
