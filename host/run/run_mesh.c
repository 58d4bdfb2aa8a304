/* The run's surface files: a PLY with the run's facts in its header and
 * colours from its main scalar, and the same surface as VTK PolyData beside
 * it (docs/io.md, "Mesh headers" and "Surfaces for ParaView"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "run_internal.h"
#include "sessile/run/generator.h"

void sessile_run_set_iteration(sessile_run *run, int iteration) {
  if (run) run->state_iteration = iteration >= 0 ? iteration + 1 : 0;
}

void sessile_run_mesh_info(const sessile_run *run, sessile_mesh_info *info) {
  *info = (sessile_mesh_info){.length_unit = "cm", .iteration = -1};
  if (!run) return;
  info->generator = run->generator;
  info->version = run->version;
  info->commit = run->commit;
  const cJSON *seed = run->config ? cJSON_GetObjectItemCaseSensitive(run->config, "seed") : NULL;
  if (cJSON_IsString(seed)) info->seed = seed->valuestring;
  if (cJSON_IsNumber(seed)) {
    snprintf(((sessile_run *)run)->seed_text, sizeof run->seed_text, "%.0f", seed->valuedouble);
    info->seed = run->seed_text;
  }
  if (run->state_iteration > 0) {
    info->iteration = run->state_iteration - 1;
    info->time = info->iteration;
    info->time_unit = "iteration";
  }
}

/* rel with its ".ply" replaced by ".vtp". */
static sessile_status vtp_name(const char *rel, char *out, size_t n) {
  size_t l = strlen(rel);
  SESSILE_CHECK(l > 4 && l < n && !strcmp(rel + l - 4, ".ply"), SESSILE_ERR_INTERNAL,
                "a surface file '%s' that is no .ply", rel);
  memcpy(out, rel, l - 4);
  memcpy(out + l - 4, ".vtp", 5);
  return SESSILE_OK;
}

/* Both files of one surface: fields and info final. */
static sessile_status write_both(sessile_run *run, const char *rel, int nparts, const sessile_mesh_part *parts,
                                 int nfields, const char *const *names, const sessile_mesh_info *info,
                                 const volatile sig_atomic_t *stop) {
  char path[4096], vrel[256];
  SESSILE_CALL(vtp_name(rel, vrel, sizeof vrel));
  SESSILE_CALL(sessile_run_file(run, rel, path, sizeof path));
  SESSILE_CALL(sessile_write_ply_info(path, nparts, parts, nfields, names, info, stop));
  SESSILE_CALL(sessile_run_file(run, vrel, path, sizeof path));
  return sessile_write_vtp(path, nparts, parts, nfields, names, info);
}

sessile_status sessile_run_write_mesh(sessile_run *run, const char *rel, int nparts, const sessile_mesh_part *parts,
                                      int nfields, const char *const *names, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop) {
  sessile_mesh_info mi;
  if (info) mi = *info;
  else sessile_run_mesh_info(run, &mi);
  if (nfields > 0) {
    if (!mi.color_by) mi.color_by = names[0];
    return write_both(run, rel, nparts, parts, nfields, names, &mi, stop);
  }
  /* no value of its own: the height, one array per part */
  SESSILE_CHECK(nparts >= 1 && nparts <= 1024 && parts, SESSILE_ERR_USAGE, "cannot write '%s': %d surface parts",
                rel, nparts);
  uint64_t tv = 0;
  for (int k = 0; k < nparts; k++) tv += parts[k].nv;
  double *z = malloc((size_t)tv * sizeof *z + 1);
  const double **zp = malloc((size_t)nparts * sizeof *zp);
  sessile_mesh_part *hp = malloc((size_t)nparts * sizeof *hp);
  sessile_status st = z && zp && hp ? SESSILE_OK
                                    : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory writing '%s'", rel);
  size_t at = 0;
  for (int k = 0; st == SESSILE_OK && k < nparts; k++) {
    for (uint32_t v = 0; v < parts[k].nv; v++) z[at + v] = parts[k].pos ? parts[k].pos[3 * (size_t)v + 2] : 0;
    zp[k] = z + at;
    hp[k] = parts[k];
    hp[k].fields = &zp[k];
    at += parts[k].nv;
  }
  const char *hname[1] = {"height"};
  mi.color_by = "height";
  if (st == SESSILE_OK) st = write_both(run, rel, nparts, hp, 1, hname, &mi, stop);
  free(z), free(zp), free(hp);
  return st;
}
