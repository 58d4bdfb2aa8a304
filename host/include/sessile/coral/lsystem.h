/* sessile — stochastic parametric L-systems for stony corals (Coralize §3.1,
 * docs/lsystem.md): a grammar (text format in docs/lsystem.md) compiled once
 * (each expression one muparser handle bound to fixed slots), derived with
 * parallel rewriting from one seeded stream, and interpreted by a 3-D turtle
 * with tropism and rotation-minimising frames into a sessile_skeleton.
 *
 * Ownership: a sessile_lsys owns its expressions; a sessile_lsys_string owns
 * its arrays (a zeroed struct is a valid empty string). */
#ifndef SESSILE_LSYSTEM_H
#define SESSILE_LSYSTEM_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "sessile/run/generator.h"
#include "sessile/run/param_table.h"
#include "sessile/run/run.h"
#include "sessile/gpu/gpu.h"
#include "sessile/mesh/surface.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* sessile/mesh/skeleton.h; only the tag here, because sessile/growth/grow_params.h (the grow
 * generator's) also names a type sessile_skeleton and the CLI includes both. */
struct sessile_skeleton;

/* A module string stored compactly: module i is the character sym[i] with
 * np[i] parameters par[off[i] .. off[i] + np[i]). */
typedef struct sessile_lsys_string {
  uint32_t n, cap;
  uint8_t *sym, *np;
  uint32_t *off;
  double *par;
  size_t npar, parcap;
} sessile_lsys_string;

void sessile_lsys_string_free(sessile_lsys_string *s);
/* The string as text ("F(1,2.5)+[A]"), parameters with %.12g; caller frees. */
sessile_status sessile_lsys_string_format(const sessile_lsys_string *s, char **text);

typedef struct sessile_lsys sessile_lsys;

enum { SESSILE_LSYS_MAX_PARAMS = 16 }; /* per module */

/* Compiles a grammar from text[0..len).  `where` names it in messages
 * ("lophelia1.lsys"): a malformed grammar is SESSILE_ERR_USAGE with the
 * message "where:line:column: what".  Defines named in override_names take
 * the given values instead of their own (an unknown name is an error). */
sessile_status sessile_lsys_parse(const char *text, size_t len, const char *where, int noverrides,
                                  const char *const *override_names, const double *override_values,
                                  sessile_lsys **out);
void sessile_lsys_destroy(sessile_lsys *g);

/* The grammar's directives: iterations, default angle (degrees), width
 * factor (! multiplies the width by it, # divides). */
int sessile_lsys_iterations(const sessile_lsys *g);
double sessile_lsys_angle(const sessile_lsys *g);
double sessile_lsys_width_factor(const sessile_lsys *g);
/* The defines after overrides (for the manifest): count, then name and value. */
int sessile_lsys_define_count(const sessile_lsys *g);
const char *sessile_lsys_define_name(const sessile_lsys *g, int i, double *value);

/* The axiom rewritten `iterations` times in parallel; every random choice
 * (stochastic productions, uniform() in expressions) from *rng.  Refuses a
 * string that would grow beyond max_modules, with an estimate of its size.
 * The grammar points at *rng for the call (uniform()): one derivation per
 * grammar at a time. */
sessile_status sessile_lsys_derive(const sessile_lsys *g, int iterations, uint64_t *rng, uint64_t max_modules,
                                   sessile_lsys_string *out);
/* The grammar's homomorphism (productions after "homomorphism:"): one
 * parallel step with them, applied to the derived string before the turtle
 * draws it (in != out).  Whether the grammar has any: */
int sessile_lsys_has_homomorphism(const sessile_lsys *g);
sessile_status sessile_lsys_homomorphism(const sessile_lsys *g, const sessile_lsys_string *in, uint64_t *rng,
                                         uint64_t max_modules, sessile_lsys_string *out);
/* One parallel rewriting step (in != out). */
sessile_status sessile_lsys_step(const sessile_lsys *g, const sessile_lsys_string *in, uint64_t *rng,
                                 uint64_t max_modules, sessile_lsys_string *out);

/* --- the turtle ------------------------------------------------------------ */
typedef struct sessile_turtle_params {
  double step;               /* cm per unit of F and f */
  double angle;              /* degrees, for + - & ^ \ / without a parameter */
  double thickness;          /* the starting radius, cm ("Thickness") */
  double thickness_variance; /* each # and ! scales the new radius by 1 + v u, u in [-1, 1] */
  double width_factor;       /* ! multiplies the radius by it, # divides (without a parameter) */
  double tropism[3];         /* T: the direction the heading bends toward (need not be unit) */
  double tropism_strength;   /* e: after each F the heading turns by e |H x T| toward T (ABOP) */
  double min_radius;         /* radii are clamped to at least this, cm (> 0) */
  int taper;                 /* 1: a segment starts at the radius the previous segment on its path
                                ended with (cones, no steps); 0: cylinders (Coralize) */
} sessile_turtle_params;

typedef struct sessile_turtle_stats {
  uint32_t segments, branches, max_depth; /* max_depth: of the drawn segments */
  double length; /* cm, drawn */
} sessile_turtle_stats;

/* Interprets the string from the origin with heading +z, left +y, up -x:
 * F draws a segment (appended to out: `up` is the rotation-minimising normal,
 * `value` the branch depth), f moves, + - yaw about up, & ^ pitch about
 * left, \ / roll about the heading, | turns around, [ ] push and pop, # !
 * change the radius.  A second parameter of F f + - & ^ \ / # ! is a
 * variance: the first is drawn uniform in [p - v, p + v] from *rng. */
sessile_status sessile_turtle_interpret(const sessile_lsys_string *s, const sessile_turtle_params *p, uint64_t *rng,
                                        struct sessile_skeleton *out, sessile_turtle_stats *stats);

/* --- the shipped grammars (host/coral/grammars/ *.lsys, embedded) ---------- */
int sessile_lsys_builtin_count(void);
/* Name ("lophelia1") and text of builtin i; NULL past the end. */
const char *sessile_lsys_builtin_name(int i);
const char *sessile_lsys_builtin_text(int i, size_t *len);
/* The builtin of that name, or NULL. */
const char *sessile_lsys_builtin_find(const char *name, size_t *len);

/* --- the generator: `sessile coral lsystem` ---------------------------------- */
typedef struct sessile_coral_lsystem_params {
  int grammar;               /* builtin grammar (enum), when no grammar file is given */
  double step;               /* cm per unit of F ("F steps") */
  double thickness;          /* cm ("Thickness") */
  double thickness_variance; /* ("Thickness Variance") */
  int mesh_detail;           /* tube sides ("Mesh Detail") */
  int geometry;              /* 0 tubes, 1 weld */
  double weld_blend, weld_cell;
  int weld_cells;
  double tropism_x, tropism_y, tropism_z, tropism_strength;
  double min_radius;
  int max_modules;
  int taper;
} sessile_coral_lsystem_params;

extern const sessile_param_table sessile_coral_lsystem_param_table;

/* Everything a run makes, before anything is written. */
typedef struct sessile_coral_lsystem_result {
  sessile_lsys_string str;        /* the string drawn (after the homomorphism, if any) */
  struct sessile_skeleton *skel; /* owned */
  sessile_surface mesh;
  double *vertex_value; /* mesh.nv: the branch order */
  sessile_turtle_stats turtle;
  int iterations;
  uint32_t *modules_per_step; /* iterations + 1 */
  double derive_s, turtle_s, mesh_s;
} sessile_coral_lsystem_result;
void sessile_coral_lsystem_result_free(sessile_coral_lsystem_result *r);

/* Derives (iterations < 0: the grammar's), interprets and meshes (weld: on
 * gpu, which may be NULL for tubes).  Streams: derivation and turtle from
 * seed, each its own (sessile_rng_stream).  stop (may be NULL): a signal's
 * flag, looked at between derivation steps and stages; once raised the
 * build ends with SESSILE_ERR_INTERRUPTED. */
sessile_status sessile_coral_lsystem_build(const sessile_coral_lsystem_params *p, const sessile_lsys *g,
                                           int iterations, uint64_t seed, sessile_gpu *gpu,
                                           const volatile sig_atomic_t *stop, sessile_coral_lsystem_result *out);
/* Writes coral/final.ply (per-vertex property "value": the branch order),
 * coral/final.obj, coral/grammar.lsys (the text used), one record per
 * derivation step and the manifest's parameters, grammar, device (gpu may
 * be NULL: tubes are host code) and statistics.  stop (may be NULL): a
 * raised flag ends it between files, and within the OBJ, with
 * SESSILE_ERR_INTERRUPTED: every file written is whole. */
sessile_status sessile_coral_lsystem_write(sessile_run *run, const sessile_coral_lsystem_params *p,
                                           const sessile_lsys *g, const char *grammar_name, const char *text,
                                           size_t len, const sessile_coral_lsystem_result *r,
                                           const sessile_gpu *gpu, const volatile sig_atomic_t *stop);

/* The same on the run framework (lsystem_gen.c), for the reef's pool: the
 * `grammar` parameter's shipped grammar, the run's iterations the derivation
 * steps (0: the grammar's; schedule() makes them one loop iteration). */
extern const sessile_generator sessile_gen_coral_lsystem;

#ifdef __cplusplus
}
#endif
#endif
