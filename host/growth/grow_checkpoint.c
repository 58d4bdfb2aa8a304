/* The growth loop's checkpoint: everything the next iteration reads from the
 * previous ones, so that a resumed run computes the same bytes as one that
 * never stopped.  Random choices need no state here: the growth kernels draw
 * from (seed, iteration, vertex) and the start position from the seed.
 *
 * Sections: surface (counts, positions, triangles), nutrient (the warm
 * start c, box nodes), summary (totals so far), series (the VTU snapshots'
 * iterations), and when they exist the flow's warm starts: flow_up
 * (immersed), flow_cmesh + flow_cup (conforming: the previous TetGen mesh,
 * from which the next warm start is interpolated) and advected (the SUPG
 * nutrient's unclipped warm start). */
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"

typedef struct blob {
  uint8_t *p;
  size_t n, cap;
  int failed;
} blob;

static void put(blob *b, const void *data, size_t n) {
  if (b->failed || !n) return;
  if (b->n + n > b->cap) {
    size_t cap = (b->n + n) * 2;
    uint8_t *q = realloc(b->p, cap);
    if (!q) {
      b->failed = 1;
      return;
    }
    b->p = q, b->cap = cap;
  }
  memcpy(b->p + b->n, data, n);
  b->n += n;
}

/* A reader over a section: every take is bounds-checked. */
typedef struct reader {
  const uint8_t *p;
  size_t n, at;
} reader;

static int take(reader *r, void *out, size_t n) {
  if (n > r->n - r->at) return 0;
  memcpy(out, r->p + r->at, n);
  r->at += n;
  return 1;
}

static sessile_status damaged(const char *what) {
  return sessile_error_set(SESSILE_ERR_IO, "the checkpoint's %s section does not fit this run (damaged, "
                                           "or written by another version); move checkpoint.bin away "
                                           "to restart from the beginning", what);
}

static void put_tetmesh(blob *b, const sessile_tetmesh *m) {
  uint32_t h[3] = {m->nnodes, m->ntets, m->nbfaces};
  put(b, h, sizeof h);
  put(b, m->xyz, (size_t)3 * m->nnodes * sizeof *m->xyz);
  put(b, m->tet, (size_t)4 * m->ntets * sizeof *m->tet);
  put(b, m->node_tags, (size_t)m->nnodes * sizeof *m->node_tags);
  put(b, m->bface, (size_t)3 * m->nbfaces * sizeof *m->bface);
  put(b, m->bface_tag, (size_t)m->nbfaces * sizeof *m->bface_tag);
}

static sessile_status take_tetmesh(reader *rd, sessile_tetmesh *m) {
  uint32_t h[3];
  if (!take(rd, h, sizeof h)) return damaged("flow_cmesh");
  size_t need = (size_t)h[0] * (3 * 8 + 4) + (size_t)h[1] * 16 + (size_t)h[2] * 16;
  if (need != rd->n - rd->at) return damaged("flow_cmesh");
  m->nnodes = h[0], m->ntets = h[1], m->nbfaces = h[2];
  m->xyz = malloc((size_t)3 * h[0] * sizeof *m->xyz + 1);
  m->tet = malloc((size_t)4 * h[1] * sizeof *m->tet + 1);
  m->node_tags = malloc((size_t)h[0] * sizeof *m->node_tags + 1);
  m->bface = malloc((size_t)3 * h[2] * sizeof *m->bface + 1);
  m->bface_tag = malloc((size_t)h[2] * sizeof *m->bface_tag + 1);
  if (!m->xyz || !m->tet || !m->node_tags || !m->bface || !m->bface_tag) {
    sessile_tetmesh_free(m);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory restoring the conforming mesh");
  }
  take(rd, m->xyz, (size_t)3 * h[0] * sizeof *m->xyz);
  take(rd, m->tet, (size_t)4 * h[1] * sizeof *m->tet);
  take(rd, m->node_tags, (size_t)h[0] * sizeof *m->node_tags);
  take(rd, m->bface, (size_t)3 * h[2] * sizeof *m->bface);
  take(rd, m->bface_tag, (size_t)h[2] * sizeof *m->bface_tag);
  return SESSILE_OK;
}

sessile_status grow_checkpoint_sections(grow_run *r, sessile_ckpt_section *sec, int *count) {
  uint32_t nb = sessile_box_nodes(&r->box);
  for (int i = 0; i < 3; i++) free(r->ck_bytes[i]), r->ck_bytes[i] = NULL;
  blob surf = {0}, cm = {0};
  uint32_t counts[2] = {r->surf.nv, r->surf.nf};
  put(&surf, counts, sizeof counts);
  put(&surf, r->surf.pos, (size_t)3 * r->surf.nv * sizeof *r->surf.pos);
  put(&surf, r->surf.tri, (size_t)3 * r->surf.nf * sizeof *r->surf.tri);
  double *c = malloc((size_t)nb * sizeof *c);
  /* the bytes stay valid until the next call (the run loop writes them) */
  r->ck_bytes[0] = surf.p, r->ck_bytes[1] = c;
  SESSILE_CHECK(c && !surf.failed, SESSILE_ERR_NO_MEMORY, "out of host memory for a checkpoint");
  SESSILE_CALL(sessile_vec_download(r->c, c));
  int n = 0;
  sec[n++] = (sessile_ckpt_section){"surface", surf.p, surf.n};
  sec[n++] = (sessile_ckpt_section){"nutrient", c, (size_t)nb * sizeof *c};
  sec[n++] = (sessile_ckpt_section){"summary", &r->sum, sizeof r->sum};
  sec[n++] = (sessile_ckpt_section){"series", r->vtu_steps, (size_t)r->nvtu * sizeof *r->vtu_steps};
  if (r->flow_ready)
    sec[n++] = (sessile_ckpt_section){"flow_up", r->up, (size_t)4 * sessile_box_nodes(&r->fbox) * sizeof *r->up};
  if (r->cup && r->cmesh.nnodes) {
    put_tetmesh(&cm, &r->cmesh);
    r->ck_bytes[2] = cm.p;
    SESSILE_CHECK(!cm.failed, SESSILE_ERR_NO_MEMORY, "out of host memory for a checkpoint");
    sec[n++] = (sessile_ckpt_section){"flow_cmesh", cm.p, cm.n};
    sec[n++] = (sessile_ckpt_section){"flow_cup", r->cup, (size_t)4 * r->cmesh.nnodes * sizeof *r->cup};
  }
  if (r->ad) sec[n++] = (sessile_ckpt_section){"advected", r->nc, (size_t)nb * sizeof *r->nc};
  *count = n;
  /* the manifest's totals at each checkpoint (the checkpoint writes it) */
  return grow_manifest_totals(r);
}

sessile_status grow_checkpoint_restore(grow_run *r, const sessile_ckpt *ck) {
  uint32_t nb = sessile_box_nodes(&r->box);
  size_t n = 0;
  const void *p = sessile_ckpt_get(ck, "surface", &n);
  reader rd = {p, n, 0};
  uint32_t counts[2];
  if (!p || !take(&rd, counts, sizeof counts) ||
      n != sizeof counts + (size_t)counts[0] * 24 + (size_t)counts[1] * 12)
    return damaged("surface");
  SESSILE_CALL(sessile_surface_reserve(&r->surf, counts[0], counts[1]));
  r->surf.nv = counts[0], r->surf.nf = counts[1];
  take(&rd, r->surf.pos, (size_t)counts[0] * 24);
  take(&rd, r->surf.tri, (size_t)counts[1] * 12);
  for (uint32_t i = 0; i < 3 * r->surf.nf; i++)
    if (r->surf.tri[i] >= r->surf.nv) return damaged("surface");

  p = sessile_ckpt_get(ck, "nutrient", &n);
  if (!p || n != (size_t)nb * sizeof(double)) return damaged("nutrient");
  double *c = malloc(n);
  SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory restoring the nutrient");
  memcpy(c, p, n);
  sessile_status s = sessile_vec_upload(r->c, c);
  free(c);
  SESSILE_CALL(s);

  p = sessile_ckpt_get(ck, "summary", &n);
  if (!p || n != sizeof r->sum) return damaged("summary");
  memcpy(&r->sum, p, n);

  p = sessile_ckpt_get(ck, "series", &n);
  if (n % sizeof(int)) return damaged("series");
  int ns = (int)(n / sizeof(int));
  r->vtu_steps = calloc((size_t)ns + 1, sizeof *r->vtu_steps);
  r->vtu_files = calloc((size_t)ns + 1, sizeof *r->vtu_files);
  SESSILE_CHECK(r->vtu_steps && r->vtu_files, SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (ns) memcpy(r->vtu_steps, p, n);
  for (int i = 0; i < ns; i++) {
    char name[64];
    snprintf(name, sizeof name, "iter_%04d.vtu", r->vtu_steps[i]);
    r->vtu_files[i] = strdup(name);
    SESSILE_CHECK(r->vtu_files[i], SESSILE_ERR_NO_MEMORY, "out of host memory");
    r->nvtu = i + 1;
  }

  if ((p = sessile_ckpt_get(ck, "flow_up", &n)) != NULL) {
    SESSILE_CALL(grow_flow_setup(r));
    if (n != (size_t)4 * sessile_box_nodes(&r->fbox) * sizeof *r->up) return damaged("flow_up");
    memcpy(r->up, p, n);
  }
  if ((p = sessile_ckpt_get(ck, "flow_cmesh", &n)) != NULL) {
    reader mr = {p, n, 0};
    SESSILE_CALL(take_tetmesh(&mr, &r->cmesh));
    p = sessile_ckpt_get(ck, "flow_cup", &n);
    if (!p || n != (size_t)4 * r->cmesh.nnodes * sizeof(double)) return damaged("flow_cup");
    r->cup = malloc(n);
    SESSILE_CHECK(r->cup, SESSILE_ERR_NO_MEMORY, "out of host memory restoring the flow");
    memcpy(r->cup, p, n);
  }
  if ((p = sessile_ckpt_get(ck, "advected", &n)) != NULL) {
    SESSILE_CALL(grow_advected_setup(r));
    if (n != (size_t)nb * sizeof *r->nc) return damaged("advected");
    memcpy(r->nc, p, n);
  }
  return SESSILE_OK;
}

/* --- the flow's warm starts around a final-only snapshot ------------------- */

static sessile_status tetmesh_copy(const sessile_tetmesh *a, sessile_tetmesh *b) {
  blob bl = {0};
  put_tetmesh(&bl, a);
  if (bl.failed) {
    free(bl.p);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory copying the conforming mesh");
  }
  reader rd = {bl.p, bl.n, 0};
  sessile_status s = take_tetmesh(&rd, b);
  free(bl.p);
  return s;
}

sessile_status grow_flow_keep(grow_run *r, grow_flow_saved *k) {
  memset(k, 0, sizeof *k);
  k->active = 1;
  k->was_ready = r->flow_ready;
  if (r->flow_ready) {
    size_t n = (size_t)4 * sessile_box_nodes(&r->fbox) * sizeof *r->up;
    k->up = malloc(n);
    SESSILE_CHECK(k->up, SESSILE_ERR_NO_MEMORY, "out of host memory for the flow's warm start");
    memcpy(k->up, r->up, n);
  }
  if (r->cup && r->cmesh.nnodes) {
    size_t n = (size_t)4 * r->cmesh.nnodes * sizeof *r->cup;
    k->cup = malloc(n);
    SESSILE_CHECK(k->cup, SESSILE_ERR_NO_MEMORY, "out of host memory for the flow's warm start");
    memcpy(k->cup, r->cup, n);
    SESSILE_CALL(tetmesh_copy(&r->cmesh, &k->cmesh));
  }
  return SESSILE_OK;
}

void grow_flow_putback(grow_run *r, grow_flow_saved *k) {
  if (!k->active) return;
  if (r->flow_ready) {
    size_t n = (size_t)4 * sessile_box_nodes(&r->fbox) * sizeof *r->up;
    if (k->up) memcpy(r->up, k->up, n);
    else if (!k->was_ready) memset(r->up, 0, n); /* as a first setup leaves it */
  }
  if (k->cup) {
    free(r->cup);
    sessile_tetmesh_free(&r->cmesh);
    r->cup = k->cup, r->cmesh = k->cmesh;
    k->cup = NULL;
    memset(&k->cmesh, 0, sizeof k->cmesh);
  } else if (r->cup) {
    free(r->cup), r->cup = NULL;
    sessile_tetmesh_free(&r->cmesh);
  }
  grow_flow_saved_free(k);
}

void grow_flow_saved_free(grow_flow_saved *k) {
  free(k->up);
  free(k->cup);
  sessile_tetmesh_free(&k->cmesh);
  memset(k, 0, sizeof *k);
}
