/* The SDS loop's outputs per frame (sds_sim.h): the surface with its
 * per-cell fields (PLY), the complex (VTU) and its series (PVD), and one
 * record per frame interval (the paper's Figure 12 figures). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io.h"
#include "sds/sds_sim.h"

sessile_status sds_write_frame(sds_sim *s, sessile_run *run, int frame, const char *ply_rel) {
  sessile_sds *o = &s->o;
  char rel[64], path[4096];
  /* the surface: boundary faces over all cells (unused cells are dropped by
   * remapping to the boundary's own vertices) */
  uint32_t *map = malloc(((size_t)o->ncells + 1) * sizeof *map);
  SESSILE_CHECK(map, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  uint32_t nv = 0;
  for (uint32_t c = 0; c < o->ncells; c++) map[c] = o->surface[c] ? nv++ : UINT32_MAX;
  int nf = 2 + (int)o->nmorph + (int)o->nstate;
  double *pos = malloc(((size_t)nv * 3 + 1) * sizeof *pos), *fields = malloc(((size_t)nv * nf + 1) * sizeof *fields);
  uint32_t *tri = malloc(((size_t)o->nfaces * 3 + 1) * sizeof *tri);
  const char **names = calloc((size_t)nf, sizeof *names);
  const double **fp = calloc((size_t)nf, sizeof *fp);
  sessile_status st = pos && fields && tri && names && fp ? SESSILE_OK
                                                       : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  if (st == SESSILE_OK) {
    for (uint32_t c = 0; c < o->ncells; c++) {
      if (map[c] == UINT32_MAX) continue;
      uint32_t v = map[c];
      memcpy(pos + 3 * (size_t)v, o->x + 3 * (size_t)c, 3 * sizeof *pos);
      fields[0 * (size_t)nv + v] = o->r[c];
      fields[1 * (size_t)nv + v] = c;
      for (uint32_t k = 0; k < o->nmorph; k++) fields[(2 + k) * (size_t)nv + v] = o->phi[(size_t)c * o->nmorph + k];
      for (uint32_t k = 0; k < o->nstate; k++)
        fields[(2 + o->nmorph + k) * (size_t)nv + v] = o->state[(size_t)c * o->nstate + k];
    }
    for (uint32_t f = 0; f < 3 * o->nfaces; f++) tri[f] = map[o->face[f]];
    names[0] = "radius", names[1] = "cell";
    for (uint32_t k = 0; k < o->nmorph; k++) names[2 + k] = sessile_sds_model_morph_name(s->model, (int)k);
    for (uint32_t k = 0; k < o->nstate; k++) names[2 + o->nmorph + k] = sessile_sds_model_state_name(s->model, (int)k);
    for (int k = 0; k < nf; k++) fp[k] = fields + (size_t)k * nv;
    sessile_mesh_part part = {"surface", pos, nv, tri, o->nfaces, NULL, fp};
    /* the PLY and its .vtp: model units, the model's time, coloured by the
     * first morphogen (the radius without one; docs/io.md) */
    sessile_mesh_info mi;
    sessile_run_mesh_info(run, &mi);
    mi.length_unit = "u", mi.time_unit = "s", mi.time = s->time, mi.color_by = names[o->nmorph ? 2 : 0];
    /* a frame is known by its exact time, not its index: frame k of 5 and
     * frame 10 k of 50 are one state and the same bytes (docs/sds.md) */
    mi.iteration = -1;
    st = sessile_run_write_mesh(run, ply_rel, 1, &part, nf, names, &mi, NULL);
  }
  if (st == SESSILE_OK && frame >= 0) {
    /* the complex: every cell with its fields, tets with their volumes */
    sessile_vtu_field pf[3 + SESSILE_SDS_MAX_VALUES * 2];
    int npf = 0;
    memset(pf, 0, sizeof pf);
    pf[npf].name = "radius", pf[npf].f64 = o->r, pf[npf++].components = 1;
    pf[npf].name = "velocity", pf[npf].f64 = o->v, pf[npf++].components = 3;
    pf[npf].name = "surface", pf[npf].u8 = o->surface, pf[npf++].components = 1;
    double *cf = malloc(((size_t)o->ncells * (o->nmorph + o->nstate) + (size_t)o->ntets + 1) * sizeof *cf);
    if (!cf) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    for (uint32_t k = 0; st == SESSILE_OK && k < o->nmorph + o->nstate && npf < (int)(sizeof pf / sizeof pf[0]); k++) {
      double *col = cf + (size_t)k * o->ncells;
      for (uint32_t c = 0; c < o->ncells; c++)
        col[c] = k < o->nmorph ? o->phi[(size_t)c * o->nmorph + k] : o->state[(size_t)c * o->nstate + (k - o->nmorph)];
      pf[npf].name = k < o->nmorph ? sessile_sds_model_morph_name(s->model, (int)k)
                                   : sessile_sds_model_state_name(s->model, (int)(k - o->nmorph));
      pf[npf].f64 = col, pf[npf++].components = 1;
    }
    if (st == SESSILE_OK) {
      double *vol = cf + (size_t)o->ncells * (o->nmorph + o->nstate);
      for (uint32_t t = 0; t < o->ntets; t++) vol[t] = sessile_sds_tet_volume(o, t);
      sessile_vtu_field tf = {.name = "volume", .f64 = vol, .components = 1};
      snprintf(rel, sizeof rel, "sds/frame_%04d.vtu", frame);
      st = sessile_run_file(run, rel, path, sizeof path);
      if (st == SESSILE_OK) st = sessile_write_vtu_tets(path, o->x, o->ncells, o->tet, o->ntets, npf, pf, 1, &tf);
    }
    free(cf);
  }
  free(map), free(pos), free(fields), free(tri), free(names), free(fp);
  return st;
}

/* The series: each frame with its simulated time, that of the first step at
 * or past the frame's nominal time (docs/sds.md, "The loop"). */
sessile_status sds_write_pvd(sessile_run *run, int nframes, const double *times) {
  char path[4096];
  char **files = calloc((size_t)nframes + 1, sizeof *files);
  sessile_status st = files ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  for (int i = 0; st == SESSILE_OK && i < nframes; i++) {
    files[i] = malloc(32);
    if (!files[i]) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    else snprintf(files[i], 32, "frame_%04d.vtu", i);
  }
  if (st == SESSILE_OK) st = sessile_run_file(run, "sds/series.pvd", path, sizeof path);
  if (st == SESSILE_OK) st = sessile_write_pvd_times(path, nframes, times, (const char *const *)files);
  for (int i = 0; files && i < nframes; i++) free(files[i]);
  free(files);
  return st;
}

sessile_status sds_record_fill(sds_sim *s, cJSON *r, int frame, double ms_per_step, uint64_t steps) {
  /* the frame's time to the bit, as the series and the step log print it
   * (cJSON's own printer may drop the last bit) */
  char time[32];
  snprintf(time, sizeof time, "%.17g", s->time);
  int ok = cJSON_AddNumberToObject(r, "frame", frame) && cJSON_AddRawToObject(r, "time", time) &&
           cJSON_AddNumberToObject(r, "cells", s->o.ncells) && cJSON_AddNumberToObject(r, "tets", s->o.ntets) &&
           cJSON_AddNumberToObject(r, "steps", (double)steps) &&
           cJSON_AddNumberToObject(r, "ms_per_step", ms_per_step) && cJSON_AddNumberToObject(r, "dt", s->dt) &&
           cJSON_AddNumberToObject(r, "divisions", (double)s->div_interval) &&
           cJSON_AddNumberToObject(r, "inversions", (double)s->inv_interval);
  s->div_interval = s->inv_interval = 0;
  SESSILE_CHECK(ok, SESSILE_ERR_NO_MEMORY, "out of host memory for a record");
  return SESSILE_OK;
}

sessile_status sds_record(sds_sim *s, sessile_run *run, int frame, double ms_per_step, uint64_t steps) {
  cJSON *r = cJSON_CreateObject();
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_status st = sds_record_fill(s, r, frame, ms_per_step, steps);
  if (st == SESSILE_OK) st = sessile_run_record(run, r);
  cJSON_Delete(r);
  return st;
}
