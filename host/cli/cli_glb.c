/* --glb: every generator's final mesh as glTF 2.0 binary beside its PLY
 * (cli_run.h, docs/io.md "glTF").  The .glb is made from the PLY the run
 * just wrote, so the two hold the same vertices and per-vertex values for
 * every generator without any generator knowing about glTF. */
#include <stdio.h>
#include <string.h>
#include "cli_run.h"
#include "sessile/io/gltf.h"

#ifndef SESSILE_VERSION
#define SESSILE_VERSION "dev"
#endif

/* A plausible colour per organism (linear RGB), matte and not metallic. */
static const struct {
  const char *cmd;
  float rgb[3];
} colours[] = {
    {"grow", {0.80f, 0.30f, 0.12f}},             /* Crella incrustans: orange-red */
    {"sponge particles", {0.85f, 0.55f, 0.20f}}, /* a yellow-ochre sponge */
    {"coral venation", {0.90f, 0.45f, 0.40f}},   /* a pink sea fan */
    {"coral lsystem", {0.92f, 0.78f, 0.62f}},    /* a pale branching coral */
    {"sds run", {0.75f, 0.62f, 0.55f}},          /* tissue */
};

/* The command's colour, or a neutral grey. */
static void organism_colour(const char *cmd, float rgb[3]) {
  rgb[0] = rgb[1] = rgb[2] = 0.7f;
  for (size_t k = 0; k < sizeof colours / sizeof *colours; k++)
    if (!strcmp(cmd, colours[k].cmd)) memcpy(rgb, colours[k].rgb, sizeof colours[k].rgb);
}

void cli_run_obj_style(const char *cmd, const cli_run_args *a, sessile_run *run) {
  float rgb[3];
  organism_colour(cmd, rgb);
  sessile_run_set_obj_style(run, a->obj_axes, cmd, rgb); /* "coral venation" -> material coral_venation */
}

sessile_status cli_run_glb(const char *cmd, const cli_run_args *a, sessile_run *run, const char *mesh_rel) {
  if (!a->glb || !run) return SESSILE_OK;
  size_t n = strlen(mesh_rel);
  SESSILE_CHECK(n > 4 && n < 200 && !strcmp(mesh_rel + n - 4, ".ply"), SESSILE_ERR_INTERNAL,
                "--glb: the final mesh '%s' is not a PLY", mesh_rel);
  char rel[256], ply[4096], glb[4096], gen[128];
  snprintf(rel, sizeof rel, "%.*s.glb", (int)(n - 4), mesh_rel);
  SESSILE_CALL(sessile_run_file(run, mesh_rel, ply, sizeof ply));
  SESSILE_CALL(sessile_run_file(run, rel, glb, sizeof glb));
  sessile_gltf_material m = {.name = cmd, .rgba = {0.7f, 0.7f, 0.7f, 1}, .metallic = 0, .roughness = 0.8f};
  organism_colour(cmd, m.rgba);
  snprintf(gen, sizeof gen, "sessile %s (%s)", SESSILE_VERSION, cmd);
  /* every organism is in centimetres (the SDS model's unit u is taken as one) */
  return sessile_gltf_write_ply(glb, ply, &m, 0.01, gen);
}
