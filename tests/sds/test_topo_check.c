/* sessile_sds_topo_check: a TetGen ball passes with the volume of its
 * surface; each kind of broken complex is caught. */
#include "test_topo_fixture.h"

static int fails(const sessile_sds_topo_complex *c, const char *what) {
  sessile_status st = sessile_sds_topo_check(c->nv, c->x, c->nt, c->tet, 0.0, NULL);
  printf("  %s -> %s\n", what, st == SESSILE_OK ? "accepted" : sessile_error_message());
  return st != SESSILE_OK;
}

int main(void) {
  sessile_sds_topo_complex cx = {0};
  fx_ball(2, 0.02, &cx);
  sessile_sds_topo_report rep;
  t_ok("ball passes the check", sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0.0, &rep));
  /* the icosphere's enclosed volume by the divergence theorem */
  sessile_surface s = {0};
  double c0[3] = {0, 0, 0};
  t_must("icosphere", sessile_surface_icosphere(2, 1.0, c0, &s));
  sessile_surface_stats ss;
  sessile_surface_stats_of(&s, &ss);
  printf("ball: %u vertices, %u tets, %u boundary faces, volume %.15g\n", cx.nv, cx.nt, rep.n_boundary_faces,
         rep.volume);
  t_check("volume = the surface's enclosed volume (rel)", fabs(rep.volume - ss.volume) / ss.volume, 1e-12);
  t_true("boundary = the icosphere's faces", rep.n_boundary_faces == s.nf);
  t_true("boundary Euler characteristic 2", rep.boundary_euler == 2);
  t_true("4 nt = 2 interior + boundary faces", 4 * cx.nt == 2 * rep.n_interior_faces + rep.n_boundary_faces);
  sessile_surface_free(&s);

  sessile_sds_topo_complex b;
  /* an inverted tet */
  fx_copy(&cx, &b);
  uint32_t x = b.tet[1];
  b.tet[1] = b.tet[2], b.tet[2] = x;
  t_true("inverted tet refused", fails(&b, "inverted tet"));
  sessile_sds_topo_complex_free(&b);
  /* a duplicated tet: a face in 3 tets or two tets on one side */
  fx_copy(&cx, &b);
  b.tet = realloc(b.tet, 4 * (b.nt + 1) * sizeof *b.tet);
  memcpy(b.tet + 4 * b.nt, b.tet, 4 * sizeof *b.tet);
  b.nt++;
  t_true("duplicate tet refused", fails(&b, "duplicate tet"));
  sessile_sds_topo_complex_free(&b);
  /* an unreferenced vertex */
  fx_copy(&cx, &b);
  b.x = realloc(b.x, 3 * (b.nv + 1) * sizeof *b.x);
  b.x[3 * b.nv] = b.x[3 * b.nv + 1] = b.x[3 * b.nv + 2] = 5;
  b.nv++;
  t_true("unreferenced vertex refused", fails(&b, "unreferenced vertex"));
  sessile_sds_topo_complex_free(&b);
  /* a removed boundary tet leaves an open... no: a removed tet is fine, a
   * removed face-sharing pair's boundary still closed; a bowtie is not */
  {
    double px[7 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
    uint32_t pt[8] = {0, 1, 2, 3, 0, 5, 4, 6};
    sessile_sds_topo_complex bow = {7, 2, px, pt};
    t_true("two tets meeting at one vertex (bowtie) refused", fails(&bow, "bowtie"));
    uint32_t pt2[8] = {0, 1, 2, 3, 4, 1, 2, 3}; /* two tets on one face, one side inverted */
    px[12] = 0.3, px[13] = 0.3, px[14] = 0.3;
    sessile_sds_topo_complex two = {5, 2, px, pt2};
    t_true("two tets on the same side of a face refused", fails(&two, "same side"));
    px[12] = 1, px[13] = 1, px[14] = 1;
    uint32_t pt3[8] = {0, 1, 2, 3, 4, 1, 3, 2}; /* two tets glued on face (1 2 3): valid */
    sessile_sds_topo_complex ok = {5, 2, px, pt3};
    t_ok("two tets glued on a face pass", sessile_sds_topo_check(5, px, 2, pt3, 0.0, &rep));
    t_check("their volume 1/6 + 1/3", fabs(rep.volume - 0.5), 1e-15);
    (void)ok;
  }
  sessile_sds_topo_complex_free(&cx);
  return t_finish(NULL);
}
