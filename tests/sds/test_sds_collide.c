/* SDS contacts (docs/sds.md, "Collisions"): the GPU's contact forces,
 * found through the surface and obstacle spatial hashes, equal the
 * brute-force host reference over every triangle, bit for bit on fp64
 * (tolerance 1e-12 relative); --fp32 (test_sds_collide_fp32) runs the
 * kernels in float, where each cell's force must be the brute force's at its
 * position or within 1e-5 of the scene's extent of it, to 1e-4 of the
 * largest force (backward_check says why).  A
 * GPU may contract a*b+c into FMA; an H100 failed random cloud 0 by 2.1e-1
 * when a cell in a face's plane was pushed along p - q, rounding noise there:
 * the push now takes the face's normal within 2^-30 of the face's size
 * (docs/sds.md, "Collisions"), and the host reference built with -mfma
 * -ffp-contract=fast then agrees with lavapipe to 3.3e-14.  Scenes: (a) two bodies in one
 * complex pressed together and a bar bent until its two ends meet, (b) a
 * ball pressed into a rock mesh, (c) random clouds with cells exactly on
 * hash cell boundaries; the host hash finds the same triangles as the brute
 * force; the contact force of a cell is -grad of its contact energy (central
 * differences); the hash table is the same bytes on every evaluation with
 * ascending buckets. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "collide_scenes.h"
#include "sessile/rng.h"
#include "sessile/sds/sds.h"
#include "testutil.h"

static int fp64;

/* fp32: float distances decide near-ties (which triangle is nearest)
 * differently from double, and the push of a cell lying on a face points
 * along rounding noise there.  So each cell's GPU force must be the brute
 * force's at its position, or at one within dx = 1e-5 of the scene's extent
 * (about 170 float ulps) in one of 26 directions: the exact answer to an
 * input that float rounding cannot tell apart (a backward error), to 1e-4 of
 * the largest force.  A wrong triangle that no such nudge explains fails. */
static void backward_check(const char *name, const sessile_sds *o, const sessile_sds_params *p, const double *fg,
                           const double *fr, double e) {
  size_t n = o->ncells;
  double fbig = 0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t k = 0; k < 3 * n; k++) fbig = fbig > fabs(fr[k]) ? fbig : fabs(fr[k]);
  for (size_t c = 0; c < n; c++)
    for (int i = 0; i < 3; i++) lo[i] = fmin(lo[i], o->x[3 * c + i]), hi[i] = fmax(hi[i], o->x[3 * c + i]);
  double ext = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2])),
         dx = 1e-5 * ext, tol = 1e-4 * fbig;
  int direct = 0, nudged = 0, bad = 0;
  for (uint32_t c = 0; c < n; c++) {
    double d0 = 0;
    for (int i = 0; i < 3; i++) d0 = fmax(d0, fabs(fg[3 * c + i] - fr[3 * c + i]));
    if (d0 <= tol) {
      direct++;
      continue;
    }
    int found = 0;
    for (int q = 0; q < 27 && !found; q++) {
      double dir[3] = {q % 3 - 1.0, q / 3 % 3 - 1.0, q / 9 - 1.0};
      double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      if (len == 0) continue;
      double xc[3], acc[3] = {0, 0, -p->gravity}, d = 0;
      for (int i = 0; i < 3; i++) xc[i] = o->x[3 * c + i] + dx * dir[i] / len;
      sessile_sds_contact ct;
      sessile_sds_contact_brute(o, p, c, xc, &ct);
      sessile_sds_contact_accel(o, p, c, xc, &ct, acc);
      for (int i = 0; i < 3; i++) d = fmax(d, fabs(fg[3 * c + i] - o->m[c] * acc[i]));
      found = d <= tol;
    }
    nudged += found, bad += !found;
    if (!found) { /* what failed, cell by cell */
      sessile_sds_contact ct;
      sessile_sds_contact_brute(o, p, c, o->x + 3 * (size_t)c, &ct);
      printf("   cell %u r %.4g: gpu %.6g %.6g %.6g ref %.6g %.6g %.6g; tri %d s %.6g obs %d s_obs %.6g\n", c, o->r[c],
             fg[3 * c], fg[3 * c + 1], fg[3 * c + 2], fr[3 * c], fr[3 * c + 1], fr[3 * c + 2], ct.tri, ct.s, ct.obs,
             ct.s_obs);
    }
  }
  char what[256];
  snprintf(what, sizeof what,
           "%s: fp32 GPU contact forces = the brute force's at each cell (%d) or within %.1e u of it (%d near-ties; "
           "%d neither; max rel %.1e)",
           name, direct, dx, nudged, bad, e);
  t_true(what, bad == 0);
}

/* GPU contact forces against m x the brute-force contact acceleration;
 * returns the number of cells with a contact (self, obstacle). */
static void compare(sessile_gpu *g, const char *name, const sessile_sds *o, const sessile_sds_params *p, int *nself,
                    int *nobs) {
  size_t n = o->ncells, n3 = 3 * n;
  double *fg = t_dalloc(n3), *fr = t_dalloc(n3), *fh = t_dalloc(n3);
  sessile_sds_contact *ct = t_xalloc(n * sizeof *ct), *ch = t_xalloc(n * sizeof *ch);
  *nself = 0, *nobs = 0;
  for (uint32_t c = 0; c < n; c++) {
    double acc[3] = {0, 0, -p->gravity};
    sessile_sds_contact_brute(o, p, c, o->x + 3 * (size_t)c, &ct[c]);
    sessile_sds_contact_accel(o, p, c, o->x + 3 * (size_t)c, &ct[c], acc);
    for (int i = 0; i < 3; i++) fr[3 * c + i] = o->m[c] * acc[i];
    *nself += ct[c].tri >= 0, *nobs += ct[c].obs >= 0;
  }
  t_must("host hash contacts", sessile_sds_contacts(o, p, ch));
  int same = 1;
  for (uint32_t c = 0; c < n; c++) same &= ct[c].tri == ch[c].tri && ct[c].obs == ch[c].obs;
  char what[160];
  snprintf(what, sizeof what, "%s: host hash finds the brute force's triangles (%d self, %d obstacle contacts)", name,
           *nself, *nobs);
  t_true(what, same);
  sessile_sds_forces_ref(o, p, 0, fh);
  snprintf(what, sizeof what, "%s: host forces_ref = brute-force contact forces (rel)", name);
  t_check(what, t_relerr(fh, fr, n3), 0);
  sessile_sds_gpu *s = NULL;
  t_must("gpu create", sessile_sds_gpu_create(g, o, p, &s));
  t_must("gpu forces", sessile_sds_gpu_forces(s, 0, fg));
  double e = t_relerr(fg, fr, n3);
  snprintf(what, sizeof what, "%s: GPU contact forces = brute force (rel; %s)", name,
           e == 0 ? "bit for bit" : "not bitwise");
  if (fp64) t_check(what, e, 1e-12);
  else backward_check(name, o, p, fg, fr, e);
  /* the storage-read kernels (lists built again with them) give the bytes of
   * the texel-read ones (shaders/sds/sds_load.glsl) */
  double *fs = t_dalloc(n3);
  sessile_sds_gpu_set_reads(s, 1);
  t_must("gpu forces, storage reads", sessile_sds_gpu_forces(s, 0, fs));
  sessile_sds_gpu_set_reads(s, 0);
  snprintf(what, sizeof what, "%s: storage-read kernels give the texel-read kernels' forces, bit for bit", name);
  t_true(what, !memcmp(fs, fg, n3 * sizeof *fg));
  free(fs);
  /* the same bytes on a second evaluation, table included, buckets ascending */
  uint32_t *t1 = NULL, *t2 = NULL;
  size_t l1 = 0, l2 = 0;
  double *fg2 = t_dalloc(n3);
  t_must("table", sessile_sds_gpu_hash_table(s, &t1, &l1));
  t_must("gpu forces again", sessile_sds_gpu_forces(s, 0, fg2));
  t_must("table again", sessile_sds_gpu_hash_table(s, &t2, &l2));
  snprintf(what, sizeof what, "%s: second evaluation: identical forces and hash table bytes", name);
  t_true(what, l1 == l2 && !memcmp(t1, t2, l1 * 4) && !memcmp(fg, fg2, n3 * sizeof *fg));
  uint32_t T = (uint32_t)((l1 - o->nfaces - 2) / 3), ok = 1;
  uint8_t *seen = t_xalloc(o->nfaces + 1);
  for (uint32_t b = 0; b < T && ok; b++) {
    ok &= t1[T + b + 1] - t1[T + b] == t1[b]; /* offsets = scanned counts */
    for (uint32_t k = t1[T + b]; k < t1[T + b + 1] && ok; k++) {
      uint32_t f = t1[3 * T + 1 + k];
      ok &= f < o->nfaces && !seen[f] && (k == t1[T + b] || t1[3 * T + k] < f);
      if (ok) seen[f] = 1;
    }
  }
  snprintf(what, sizeof what, "%s: hash table of %u buckets: counts scan to offsets, each face once, buckets ascending",
           name, T);
  t_true(what, ok && t1[2 * T] == o->nfaces);
  free(seen), free(t1), free(t2), free(fg2);
  sessile_sds_gpu_destroy(s);
  free(fg), free(fr), free(fh), free(ct), free(ch);
}

/* -grad of a cell's contact energy (its triangle held fixed) against its
 * contact force, for every cell with a contact. */
static void finite_differences(const char *name, sessile_sds *o, const sessile_sds_params *p) {
  double err = 0, scale = 0;
  int cells = 0, skipped = 0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    double *x = o->x + 3 * (size_t)c, acc[3] = {0, 0, 0};
    sessile_sds_contact ct;
    sessile_sds_contact_brute(o, p, c, x, &ct);
    if (ct.tri < 0 && ct.obs < 0) continue;
    /* the unsigned surface distance has a kink on the triangle (|s|): no
     * derivative there (the snapped clouds put cells in a face's plane) */
    if ((ct.tri >= 0 && fabs(ct.s) < 1e-6) || (ct.obs >= 0 && fabs(ct.s_obs) < 1e-6)) {
      skipped++;
      continue;
    }
    cells++;
    sessile_sds_contact_accel(o, p, c, x, &ct, acc);
    for (int i = 0; i < 3; i++) {
      const double h = 1e-7;
      double x0 = x[i], u[2], a2[3] = {0, 0, 0};
      for (int sg = 0; sg < 2; sg++) {
        x[i] = x0 + (sg ? -h : h);
        sessile_sds_contact cs;
        sessile_sds_contact_brute(o, p, c, x, &cs);
        u[sg] = sessile_sds_contact_accel(o, p, c, x, &cs, a2);
      }
      x[i] = x0;
      double e1 = fabs(-(u[0] - u[1]) / (2 * h) - acc[i]);
      if (getenv("SDS_TRACE") && e1 > 1e-3) {
        sessile_sds_contact c0, c1;
        x[i] = x0 + h;
        sessile_sds_contact_brute(o, p, c, x, &c0);
        x[i] = x0 - h;
        sessile_sds_contact_brute(o, p, c, x, &c1);
        x[i] = x0;
        printf("cell %u axis %d: tri %d s %.17g | +h tri %d s %.17g | -h tri %d s %.17g; obs %d %g, %d %g, %d %g\n", c,
               i, ct.tri, ct.s, c0.tri, c0.s, c1.tri, c1.s, ct.obs, ct.s_obs, c0.obs, c0.s_obs, c1.obs, c1.s_obs);
      }
      err = fmax(err, e1);
      scale = fmax(scale, fabs(acc[i]));
    }
  }
  char what[160];
  snprintf(what, sizeof what,
           "%s: contact force = -grad of the cell's contact energy (%d cells, %d on a face "
           "skipped; rel to max)",
           name, cells, skipped);
  t_check(what, scale > 0 ? err / scale : 1, 1e-6);
}

int main(int argc, char **argv) {
  sessile_gpu *g = t_gpu(argc > 1 && !strcmp(argv[1], "--fp32") ? 32 : 0);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  sessile_sds_params p;
  int ns = 0, no = 0;

  /* (a) two bodies pressed together: overlapping by 0.06 u (cells behind
   * the other body's faces) and 0.05 u apart (in front) */
  for (int k = 0; k < 2; k++) {
    const double c0[3] = {-1.0 + (k ? 0.03 : -0.025), 0, 0}, c1[3] = {1.0 - (k ? 0.03 : -0.025), 0.013, 0.007};
    sessile_sds o = {0};
    two_bodies(3, c0, c1, &o);
    contact_only(&p);
    compare(g, k ? "two bodies overlapping" : "two bodies 0.05 apart", &o, &p, &ns, &no);
    t_true("  they touch: some cells in contact", ns >= 4);
    finite_differences(k ? "two bodies overlapping" : "two bodies 0.05 apart", &o, &p);
    sessile_sds_free(&o);
  }
  {
    sessile_sds o = {0};
    bent_bar(0.02, &o);
    contact_only(&p);
    compare(g, "bar bent until its ends meet", &o, &p, &ns, &no);
    t_true("  its ends touch: some cells in contact", ns >= 4);
    finite_differences("bent bar", &o, &p);
    sessile_sds_free(&o);
  }
  /* (b) a ball pressed 0.08 u into a rock */
  {
    sessile_sds o = {0};
    sessile_surface rock = {0};
    ball_and_rock(3, 1.0, 0.0123, 0.92, &o, &rock); /* off the rock's symmetry planes */
    contact_only(&p);
    p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
    compare(g, "ball pressed on a rock", &o, &p, &ns, &no);
    t_true("  cells touch the rock", no >= 4);
    finite_differences("ball on a rock", &o, &p);
    sessile_sds_free(&o);
    sessile_surface_free(&rock);
  }
  /* (b') the ball held just over the rock with the rock's adhesion: cells
   * in the penalty and in both halves of the adhesion's tent (docs/sds.md,
   * "Adhesion and friction"), whose force is -grad of its potential too */
  {
    sessile_sds o = {0};
    sessile_surface rock = {0};
    ball_and_rock(3, 1.0, 0.0123, 1.04, &o, &rock);
    contact_only(&p);
    p.adhesion = 5;
    p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
    compare(g, "ball over a rock, adhesion", &o, &p, &ns, &no);
    int band = 0;
    for (uint32_t c = 0; c < o.ncells; c++) {
      sessile_sds_contact ct;
      sessile_sds_contact_brute(&o, &p, c, o.x + 3 * (size_t)c, &ct);
      band += ct.obs >= 0 && ct.s_obs >= p.contact_scale * o.r[c];
    }
    t_true("  cells in the adhesion's band and in contact", band >= 4 && no > band);
    finite_differences("ball over a rock, adhesion", &o, &p);
    sessile_sds_free(&o);
    sessile_surface_free(&rock);
  }
  /* (c) random clouds: the cells of an import scattered in a cube (the
   * boundary faces become a random triangle soup), an obstacle of random
   * triangles; a quarter of the coordinates put exactly on multiples of
   * the hash cell size h (1.5 x the mean boundary side, as the upload). */
  for (int trial = 0; trial < 3; trial++) {
    const double ctr[3] = {0, 0, 0};
    sessile_sds o = {0};
    t_must("import", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &o));
    uint64_t rng = sessile_rng_stream(2026, (uint64_t)trial);
    double side = 1.2 + 0.4 * trial;
    for (size_t k = 0; k < 3 * (size_t)o.ncells; k++) o.x[k] = side * sessile_rng_uniform(&rng);
    double h = 0;
    for (uint32_t f = 0; f < o.nfaces; f++)
      for (int k = 0; k < 3; k++) {
        const double *a = o.x + 3 * (size_t)o.face[3 * f + k], *b = o.x + 3 * (size_t)o.face[3 * f + (k + 1) % 3];
        h += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
      }
    h *= 1.5 / (3.0 * o.nfaces); /* SDS_HASH_CELL x the mean side, as the upload */
    for (size_t k = 0; k < 3 * (size_t)o.ncells; k += 4) o.x[k] = h * floor(o.x[k] / h);
    const uint32_t nv = 60, nf = 20;
    double *pos = t_dalloc(3 * nv);
    uint32_t *tri = t_xalloc(3 * nf * sizeof *tri);
    for (uint32_t k = 0; k < 3 * nv; k++) pos[k] = side * sessile_rng_uniform(&rng);
    for (uint32_t k = 0; k < 3 * nf; k++) tri[k] = k;
    contact_only(&p);
    p.obstacle.nv = nv, p.obstacle.nf = nf, p.obstacle.pos = pos, p.obstacle.tri = tri;
    char name[64];
    snprintf(name, sizeof name, "random cloud %d (side %.1f)", trial, side);
    compare(g, name, &o, &p, &ns, &no);
    t_true("  contacts of both kinds", ns >= 4 && no >= 2);
    finite_differences(name, &o, &p);
    free(pos), free(tri);
    sessile_sds_free(&o);
  }
  return t_finish(g);
}
