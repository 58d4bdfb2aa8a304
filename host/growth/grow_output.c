/* The files of `sessile grow`: snapshots (PLY, EXR slices, VTU + PVD) and
 * the final meshes, each listed in the run directory (sessile/run/run.h) and
 * written through host/io's atomic writers. */
#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "grow_internal.h"
#include "sessile/io/io.h"
#include "sessile/run/generator.h"

/* Parses a --slices spec against the box's extent mx; bare axes go through
 * center.  Each plane once. */
static sessile_status parse_planes(const char *spec, const double mx[3], const double center[3],
                                   grow_plane *planes, int *nplanes) {
  *nplanes = 0;
  const char *s = spec;
  while (*s) {
    const char *e = strchr(s, ',');
    size_t len = e ? (size_t)(e - s) : strlen(s);
    char tok[64];
    SESSILE_CHECK(len > 0 && len < sizeof tok, SESSILE_ERR_USAGE,
                  "--slices: bad plane list '%.80s' (e.g. 'x,y,z' or 'z=3.5,x=19.2')", spec);
    memcpy(tok, s, len);
    tok[len] = 0;
    SESSILE_CHECK(*nplanes < 16, SESSILE_ERR_USAGE, "--slices: at most 16 planes");
    grow_plane *pl = &planes[*nplanes];
    SESSILE_CHECK(tok[0] == 'x' || tok[0] == 'y' || tok[0] == 'z', SESSILE_ERR_USAGE,
                  "--slices: plane '%s' must start with x, y or z", tok);
    pl->axis = tok[0] - 'x';
    if (tok[1] == 0) {
      /* through the sponge: its initial centre */
      pl->value = center[pl->axis];
      snprintf(pl->name, sizeof pl->name, "%c", tok[0]);
    } else {
      char *end = NULL;
      SESSILE_CHECK(tok[1] == '=', SESSILE_ERR_USAGE, "--slices: plane '%s' must be 'AXIS' or 'AXIS=VALUE'", tok);
      /* decimal only: strtod alone would take "0x1p3", "inf" or blanks */
      SESSILE_CHECK(tok[2] && strspn(tok + 2, "0123456789.eE+-") == strlen(tok + 2), SESSILE_ERR_USAGE,
                    "--slices: '%s' needs a decimal number of cm after '='", tok);
      pl->value = strtod(tok + 2, &end);
      SESSILE_CHECK(end != tok + 2 && !*end && isfinite(pl->value) && pl->value >= 0 &&
                        pl->value <= mx[pl->axis],
                    SESSILE_ERR_USAGE, "--slices: '%s' is not inside the box (%c in [0, %g] cm)",
                    tok, tok[0], mx[pl->axis]);
      snprintf(pl->name, sizeof pl->name, "%c%g", tok[0], pl->value);
    }
    for (int k = 0; k < *nplanes; k++)
      SESSILE_CHECK(strcmp(planes[k].name, pl->name), SESSILE_ERR_USAGE,
                    "--slices: plane '%s' is given twice", pl->name);
    (*nplanes)++;
    s += len;
    if (*s == ',') s++;
  }
  return SESSILE_OK;
}

sessile_status grow_parse_planes(grow_run *r) {
  double mx[3];
  sessile_box_max(&r->box, mx);
  return parse_planes(r->o->slices ? r->o->slices : "", mx, r->center, r->planes, &r->nplanes);
}

sessile_status sessile_grow_check_options(const sessile_grow_params *p, const sessile_grow_options *o) {
  SESSILE_CALL(sessile_params_validate(p));
  SESSILE_CHECK(o->iterations >= 0 && o->every >= 0, SESSILE_ERR_USAGE,
                "iterations and every must be >= 0");
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {(uint32_t)p->box_cells_x, (uint32_t)p->box_cells_y, (uint32_t)p->box_cells_z};
  sessile_box box;
  memset(&box, 0, sizeof box);
  SESSILE_CALL(sessile_box_make(origin, p->box_base_cell, cells, p->box_resolution, &box));
  double mx[3];
  sessile_box_max(&box, mx);
  const double center[3] = {mx[0] / 2, mx[1] / 2, 0};
  grow_plane planes[16];
  int n = 0;
  return parse_planes(o->slices ? o->slices : "", mx, center, planes, &n);
}

static sessile_status write_pvd(grow_run *r) {
  char path[4096];
  SESSILE_CALL(sessile_run_file(r->o->run, "fields/series.pvd", path, sizeof path));
  return sessile_write_pvd(path, r->nvtu, r->vtu_steps, (const char *const *)r->vtu_files);
}

/* The run file rel (printf-style) as a path. */
static sessile_status run_path(grow_run *r, char *path, size_t n, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static sessile_status run_path(grow_run *r, char *path, size_t n, const char *fmt, ...) {
  char rel[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(rel, sizeof rel, fmt, ap);
  va_end(ap);
  return sessile_run_file(r->o->run, rel, path, n);
}

/* The surface (PLY and .vtp, coloured by height) after iteration it, saying
 * plainly which state it is: the fields and slices of iteration it were
 * solved on the surface before it grew (docs/io.md, "One state per
 * snapshot"). */
static sessile_status write_surface(grow_run *r, const char *rel, int it) {
  sessile_mesh_info mi;
  sessile_run_mesh_info(r->o->run, &mi);
  mi.iteration = it, mi.time = it, mi.time_unit = "iteration";
  char state[256];
  if (it > 0)
    snprintf(state, sizeof state,
             "surface after iteration %d (grown and remeshed); the nutrient and flow of iteration %d "
             "(fields/iter_%04d.vtu, slices/iter_%04d_*.exr) were solved on the surface before it grew",
             it, it, it, it);
  else snprintf(state, sizeof state, "the initial surface (no iteration run)");
  mi.state = state;
  sessile_mesh_part part = {"surface", r->surf.pos, r->surf.nv, r->surf.tri, r->surf.nf, r->normals, NULL};
  return sessile_run_write_mesh(r->o->run, rel, 1, &part, 0, NULL, &mi, NULL);
}

/* sponge/series.pvd: the surfaces written so far (the --every grid and
 * iteration it), timestep = iteration, for ParaView to play; derived from the
 * schedule, so a resume that removes an off-grid last snapshot rewrites it
 * at its next snapshot. */
static sessile_status write_surface_pvd(grow_run *r, int it) {
  int *steps = malloc(((size_t)it + 1) * sizeof *steps), n = 0;
  char **files = calloc((size_t)it + 1, sizeof *files);
  sessile_status s = steps && files ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (int k = 1; s == SESSILE_OK && k <= it; k++) {
    if (k < it && sessile_gen_snapshot_kind(r->su, k) != 1) continue;
    files[n] = malloc(32);
    if (!files[n]) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else snprintf(files[n], 32, "iter_%04d.vtp", k), steps[n++] = k;
  }
  char path[4096];
  if (s == SESSILE_OK) s = sessile_run_file(r->o->run, "sponge/series.pvd", path, sizeof path);
  if (s == SESSILE_OK) s = sessile_write_pvd(path, n, steps, (const char *const *)files);
  for (int k = 0; files && k < n; k++) free(files[k]);
  free(files), free(steps);
  return s;
}

sessile_status grow_write_snapshot(grow_run *r, int it) {
  char path[4096], rel[64];
  snprintf(rel, sizeof rel, "sponge/iter_%04d.ply", it);
  SESSILE_CALL(write_surface(r, rel, it));
  if (r->o->run) SESSILE_CALL(write_surface_pvd(r, it));
  if (!r->nplanes && !r->o->fields) return SESSILE_OK;

  uint32_t nodes = sessile_box_nodes(&r->box);
  double *c = malloc((size_t)nodes * sizeof *c);
  uint32_t *solid = malloc((size_t)nodes * sizeof *solid);
  uint8_t *mask = malloc(nodes);
  sessile_status s = SESSILE_OK;
  if (!c || !solid || !mask) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a snapshot");
  if (s == SESSILE_OK) s = sessile_vec_download(r->c, c);
  if (s == SESSILE_OK) s = sessile_buffer_download(r->solid, 0, solid, (size_t)nodes * 4);
  /* The flow's channels (m/s, Pa) when this iteration solved it. */
  double *uc = NULL;
  int flow = r->flow_valid;
  if (s == SESSILE_OK && flow) {
    uc = malloc((size_t)nodes * 4 * sizeof *uc);
    if (!uc) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a snapshot");
    for (uint32_t i = 0; uc && i < nodes; i++) {
      const double *u = r->ufine + 3 * (size_t)i;
      uc[i] = u[0], uc[nodes + i] = u[1], uc[2 * (size_t)nodes + i] = u[2];
      uc[3 * (size_t)nodes + i] = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    }
  }
  for (int i = 0; s == SESSILE_OK && i < r->nplanes; i++) {
    sessile_slice_channel ch[6] = {{"c", c}};
    int nch = 1;
    if (flow) {
      ch[1] = (sessile_slice_channel){"ux", uc};
      ch[2] = (sessile_slice_channel){"uy", uc + nodes};
      ch[3] = (sessile_slice_channel){"uz", uc + 2 * (size_t)nodes};
      ch[4] = (sessile_slice_channel){"umag", uc + 3 * (size_t)nodes};
      ch[5] = (sessile_slice_channel){"p", r->pfine};
      nch = 6;
    }
    s = run_path(r, path, sizeof path, "slices/iter_%04d_%s.exr", it, r->planes[i].name);
    if (s == SESSILE_OK) s = sessile_write_slice_exr(path, &r->box, (sessile_axis)r->planes[i].axis, r->planes[i].value, nch,
                                ch, it);
  }
  free(uc);
  if (s == SESSILE_OK && r->o->fields) {
    for (uint32_t i = 0; i < nodes; i++) mask[i] = solid[i] != 0;
    sessile_point_data pd[4] = {{"c", c, NULL, 1}, {"solid", NULL, mask, 1}, {"u", r->ufine, NULL, 3},
                                {"p", r->pfine, NULL, 1}};
    char name[64];
    snprintf(name, sizeof name, "iter_%04d.vtu", it);
    s = run_path(r, path, sizeof path, "fields/%s", name);
    if (s == SESSILE_OK) s = sessile_write_vtu(path, &r->box, flow ? 4 : 2, pd);
    if (s == SESSILE_OK) {
      int *steps = realloc(r->vtu_steps, (size_t)(r->nvtu + 1) * sizeof *steps);
      if (steps) r->vtu_steps = steps;
      char **files = realloc(r->vtu_files, (size_t)(r->nvtu + 1) * sizeof *files);
      if (files) r->vtu_files = files;
      char *dup = strdup(name);
      if (!steps || !files || !dup) {
        free(dup);
        s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
      } else {
        r->vtu_steps[r->nvtu] = it;
        r->vtu_files[r->nvtu++] = dup;
        s = write_pvd(r);
      }
    }
  }
  free(c);
  free(solid);
  free(mask);
  return s;
}

sessile_status grow_forget_snapshot(grow_run *r, int it) {
  char rel[256];
  snprintf(rel, sizeof rel, "sponge/iter_%04d.ply", it);
  SESSILE_CALL(sessile_run_remove_file(r->o->run, rel));
  snprintf(rel, sizeof rel, "sponge/iter_%04d.vtp", it);
  SESSILE_CALL(sessile_run_remove_file(r->o->run, rel));
  for (int i = 0; i < r->nplanes; i++) {
    snprintf(rel, sizeof rel, "slices/iter_%04d_%s.exr", it, r->planes[i].name);
    SESSILE_CALL(sessile_run_remove_file(r->o->run, rel));
  }
  snprintf(rel, sizeof rel, "fields/iter_%04d.vtu", it);
  SESSILE_CALL(sessile_run_remove_file(r->o->run, rel));
  int k = 0;
  for (int i = 0; i < r->nvtu; i++) {
    if (r->vtu_steps[i] == it) {
      free(r->vtu_files[i]);
      continue;
    }
    r->vtu_steps[k] = r->vtu_steps[i];
    r->vtu_files[k++] = r->vtu_files[i];
  }
  int changed = k != r->nvtu;
  r->nvtu = k;
  return changed ? write_pvd(r) : SESSILE_OK;
}

sessile_status grow_write_final(grow_run *r) {
  SESSILE_CALL(write_surface(r, "sponge/final.ply", r->sum.iterations));
  sessile_mesh_info mi;
  sessile_run_mesh_info(r->o->run, &mi);
  mi.iteration = r->sum.iterations;
  return sessile_run_write_obj(r->o->run, "sponge/final.obj", &r->surf, r->normals, &mi, NULL);
}
