/* Views and the camera fitted to the bounds; the grid spacing.
 *
 * World: z up, in cm.  A view is an azimuth (from +x toward +y) and an
 * elevation of the direction from the target to the eye: front looks along
 * +y (eye at -y), side along -x (eye at +x), top down -z with +y up on the
 * picture, oblique from the front right and 30 degrees above.  Turntable
 * frames add to the azimuth.  Clip space is Vulkan's: y down, depth 0..1. */
#include <math.h>
#include <string.h>
#include "mesh_internal.h"

#define PI 3.14159265358979323846

static const struct {
  const char *name;
  double azimuth, elevation;
} views[] = {
    {"oblique", -60.0, 30.0},
    {"side", 0.0, 0.0},
    {"top", -90.0, 90.0},
    {"front", -90.0, 0.0},
};

const char *sessile_render_view_names(void) { return "oblique, side, top, front"; }

int render_view_angles_(const char *view, double *azimuth, double *elevation) {
  for (size_t i = 0; i < sizeof views / sizeof views[0]; i++)
    if (view && strcmp(view, views[i].name) == 0) {
      *azimuth = views[i].azimuth;
      *elevation = views[i].elevation;
      return 1;
    }
  return 0;
}

double render_grid_spacing_(double span) {
  if (!(span > 0)) return 1.0;
  double target = span / 10.0;
  double p = pow(10.0, floor(log10(target)));
  const double nice[4] = {1, 2, 5, 10};
  for (int i = 0; i < 4; i++)
    if (nice[i] * p >= target * (1 - 1e-12)) return nice[i] * p;
  return 10 * p;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static double dot3f(const float *a, const double *b) {
  return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

static void normalize3(double *a) {
  double l = sqrt(dot3(a, a));
  for (int k = 0; k < 3; k++) a[k] /= l;
}

void render_camera_fit_(const char *view, double extra_azimuth, int ortho, uint32_t width,
                        uint32_t height, const float *pts, size_t npts, const double lo[3],
                        const double hi[3], render_camera *cam) {
  double az = 0, el = 0;
  render_view_angles_(view, &az, &el);
  az = (az + extra_azimuth) * PI / 180.0;
  el = el * PI / 180.0;
  double *t = cam->toward, *r = cam->right, *u = cam->up;
  t[0] = cos(el) * cos(az);
  t[1] = cos(el) * sin(az);
  t[2] = sin(el);
  if (fabs(el - PI / 2) < 1e-9) { /* straight down: keep the azimuth's right */
    t[0] = t[1] = 0;
    t[2] = 1;
  }
  /* right = forward x z = -t x z, taken from the azimuth so top views work */
  r[0] = -sin(az);
  r[1] = cos(az);
  r[2] = 0;
  /* up = right x forward = t x r */
  u[0] = t[1] * r[2] - t[2] * r[1];
  u[1] = t[2] * r[0] - t[0] * r[2];
  u[2] = t[0] * r[1] - t[1] * r[0];
  normalize3(u);
  /* The extent of the points along right, up and toward: the picture is
   * centred on the middle of the projected points, not of their box, so a
   * round mesh is not framed by its box's corners. */
  double mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < npts; i++) {
    const float *p = pts + 3 * i;
    double d[3] = {dot3f(p, r), dot3f(p, u), dot3f(p, t)};
    for (int k = 0; k < 3; k++) {
      mn[k] = fmin(mn[k], d[k]);
      mx[k] = fmax(mx[k], d[k]);
    }
  }
  double c[3];
  for (int k = 0; k < 3; k++)
    c[k] = (mn[0] + mx[0]) / 2 * r[k] + (mn[1] + mx[1]) / 2 * u[k] + (mn[2] + mx[2]) / 2 * t[k];
  double hx = (mx[0] - mn[0]) / 2, hy = (mx[1] - mn[1]) / 2, hz = (mx[2] - mn[2]) / 2;
  double aspect = (double)width / (double)height;
  const double margin = 1.1;
  /* Everything drawn lies in lo..hi (mesh and grid), within R of c. */
  double R = 0;
  for (int i = 0; i < 8; i++) {
    double p[3] = {i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]};
    double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    R = fmax(R, sqrt(dot3(d, d)));
  }
  R = fmax(R, 1e-6);
  double sx, sy, dist, near, far;
  if (ortho) {
    /* half-widths in cm of the view: the projected box with a margin */
    double wx = fmax(hx, hy * aspect) * margin, wy = wx / aspect;
    if (wx <= 0) wx = wy = 1;
    sx = 1.0 / wx;
    sy = 1.0 / wy;
    cam->px_per_cm = (double)width / (2 * wx);
    dist = 2 * R;
    near = R;
    far = 3 * R;
  } else {
    const double fovy = 30.0 * PI / 180.0;
    double ty = tan(fovy / 2), tx = ty * aspect;
    dist = hz + margin * fmax(hx / tx, hy / ty);
    dist = fmax(dist, 1e-6);
    sx = 1.0 / tx;
    sy = 1.0 / ty;
    near = fmax(dist - R, dist * 1e-3);
    far = dist + R;
    cam->px_per_cm = (double)height / (2 * dist * ty);
  }
  for (int k = 0; k < 3; k++) cam->eye[k] = c[k] + dist * t[k];
  cam->ortho = ortho;
  /* view: camera coordinates (x right, y up, z toward the viewer) */
  double e[3] = {cam->eye[0], cam->eye[1], cam->eye[2]};
  double V[3][4] = {{r[0], r[1], r[2], -dot3(r, e)},
                    {u[0], u[1], u[2], -dot3(u, e)},
                    {t[0], t[1], t[2], -dot3(t, e)}};
  double P[4][4];
  memset(P, 0, sizeof P);
  if (ortho) {
    P[0][0] = sx;
    P[1][1] = -sy; /* Vulkan: y down */
    P[2][2] = -1.0 / (far - near);
    P[2][3] = -near / (far - near);
    P[3][3] = 1;
  } else {
    P[0][0] = sx;
    P[1][1] = -sy;
    P[2][2] = far / (near - far);
    P[2][3] = near * far / (near - far);
    P[3][2] = -1;
  }
  /* M = P [V; 0 0 0 1], stored column-major */
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      double s = P[i][3] * (j == 3 ? 1.0 : 0.0);
      for (int k = 0; k < 3; k++) s += P[i][k] * V[k][j];
      cam->clip_from_world[j * 4 + i] = s;
    }
}
