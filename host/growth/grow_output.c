/* The run directory of `sessile grow`: folders, snapshots (PLY, EXR slices,
 * VTU + PVD) and the final meshes.  Every file goes through host/io's atomic
 * writers. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "grow_internal.h"
#include "sessile/io.h"

sessile_status grow_parse_planes(grow_run *r) {
  const char *spec = r->o->slices ? r->o->slices : "";
  r->nplanes = 0;
  const char *s = spec;
  while (*s) {
    const char *e = strchr(s, ',');
    size_t len = e ? (size_t)(e - s) : strlen(s);
    char tok[64];
    SESSILE_CHECK(len > 0 && len < sizeof tok, SESSILE_ERR_USAGE,
                  "--slices: bad plane list '%s' (e.g. 'x,y,z' or 'z=3.5,x=19.2')", spec);
    memcpy(tok, s, len);
    tok[len] = 0;
    SESSILE_CHECK(r->nplanes < 16, SESSILE_ERR_USAGE, "--slices: at most 16 planes");
    grow_plane *pl = &r->planes[r->nplanes];
    SESSILE_CHECK(tok[0] == 'x' || tok[0] == 'y' || tok[0] == 'z', SESSILE_ERR_USAGE,
                  "--slices: plane '%s' must start with x, y or z", tok);
    pl->axis = tok[0] - 'x';
    double mx[3];
    sessile_box_max(&r->box, mx);
    if (tok[1] == 0) {
      /* through the sponge: its initial centre */
      pl->value = r->center[pl->axis];
      snprintf(pl->name, sizeof pl->name, "%c", tok[0]);
    } else {
      char *end = NULL;
      SESSILE_CHECK(tok[1] == '=', SESSILE_ERR_USAGE, "--slices: plane '%s' must be 'AXIS' or 'AXIS=VALUE'", tok);
      pl->value = strtod(tok + 2, &end);
      SESSILE_CHECK(end != tok + 2 && !*end && isfinite(pl->value) && pl->value >= 0 &&
                        pl->value <= mx[pl->axis],
                    SESSILE_ERR_USAGE, "--slices: '%s' is not inside the box (%c in [0, %g] cm)",
                    tok, tok[0], mx[pl->axis]);
      snprintf(pl->name, sizeof pl->name, "%c%g", tok[0], pl->value);
    }
    r->nplanes++;
    s += len;
    if (*s == ',') s++;
  }
  return SESSILE_OK;
}

static sessile_status subdir(const char *out, const char *name) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", out, name);
  SESSILE_CHECK(sessile_mkdirs(path) == SESSILE_OK, SESSILE_ERR_USAGE,
                "cannot create the output folder '%s': %s", path, sessile_error_message());
  SESSILE_CHECK(access(path, W_OK) == 0, SESSILE_ERR_USAGE,
                "the output folder '%s' is not writable: %s", path, strerror(errno));
  return SESSILE_OK;
}

sessile_status grow_prepare_outdir(grow_run *r) {
  const char *out = r->o->out_dir;
  SESSILE_CHECK(strlen(out) < 3000, SESSILE_ERR_USAGE, "output folder name too long");
  SESSILE_CHECK(sessile_mkdirs(out) == SESSILE_OK, SESSILE_ERR_USAGE,
                "cannot create the output folder '%s': %s", out, sessile_error_message());
  SESSILE_CHECK(access(out, W_OK) == 0, SESSILE_ERR_USAGE, "the output folder '%s' is not writable: %s",
                out, strerror(errno));
  SESSILE_CALL(subdir(out, "sponge"));
  if (r->nplanes) SESSILE_CALL(subdir(out, "slices"));
  if (r->o->fields) SESSILE_CALL(subdir(out, "fields"));
  return SESSILE_OK;
}

static sessile_status write_pvd(grow_run *r) {
  char path[4096];
  snprintf(path, sizeof path, "%s/fields/series.pvd", r->o->out_dir);
  return sessile_write_pvd(path, r->nvtu, r->vtu_steps, (const char *const *)r->vtu_files);
}

sessile_status grow_write_snapshot(grow_run *r, int it, const double *normals) {
  const char *out = r->o->out_dir;
  char path[4096];
  snprintf(path, sizeof path, "%s/sponge/iter_%04d.ply", out, it);
  SESSILE_CALL(sessile_write_ply(path, &r->surf, normals, 0, NULL, NULL));
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
    snprintf(path, sizeof path, "%s/slices/iter_%04d_%s.exr", out, it, r->planes[i].name);
    s = sessile_write_slice_exr(path, &r->box, (sessile_axis)r->planes[i].axis, r->planes[i].value, nch,
                                ch, it);
  }
  free(uc);
  if (s == SESSILE_OK && r->o->fields) {
    for (uint32_t i = 0; i < nodes; i++) mask[i] = solid[i] != 0;
    sessile_point_data pd[4] = {{"c", c, NULL, 1}, {"solid", NULL, mask, 1}, {"u", r->ufine, NULL, 3},
                                {"p", r->pfine, NULL, 1}};
    char name[64];
    snprintf(name, sizeof name, "iter_%04d.vtu", it);
    snprintf(path, sizeof path, "%s/fields/%s", out, name);
    s = sessile_write_vtu(path, &r->box, flow ? 4 : 2, pd);
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

sessile_status grow_write_final(grow_run *r, const double *normals) {
  char path[4096];
  snprintf(path, sizeof path, "%s/sponge/final.ply", r->o->out_dir);
  SESSILE_CALL(sessile_write_ply(path, &r->surf, normals, 0, NULL, NULL));
  snprintf(path, sizeof path, "%s/sponge/final.obj", r->o->out_dir);
  SESSILE_CALL(sessile_write_obj(path, &r->surf, normals));
  return SESSILE_OK;
}
