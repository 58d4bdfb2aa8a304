// The project's only C++: copies a tg_plc into TetGen's tetgenio, calls
// tetrahedralize and copies the mesh back into malloc'd arrays.  TetGen 1.5
// (Debian's libtet, built with TETLIBRARY) reports every failure by
// terminatetetgen() -> `throw int`; allocations throw std::bad_alloc.  All of
// it is caught here: no exception crosses into C.  tetgenio's destructor frees
// its arrays with delete[], so the input is filled with new[] and both
// tetgenio objects clean up on every path, the exceptional ones included.
#define TETLIBRARY
#define terminatetetgen tetgen_header_terminatetetgen /* the header's copy, unused */
#include <tetgen.h>
#undef terminatetetgen

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include <fcntl.h>
#include <mutex>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tetgen_plc.h"

// TetGen 1.5.0 (Debian 12) frees the mesh's memory pools in
// terminatetetgen() and then throws; tetrahedralize()'s local tetgenmesh is
// destroyed while the exception unwinds and frees the same pools again: a
// double free that crashes on every error (self-intersecting input
// included).  libtet calls terminatetetgen through its PLT (a weak, default
// visibility symbol), so this definition in the executable takes its place:
// it only throws, and the unwinding destructor frees the mesh once.
void terminatetetgen(tetgenmesh *, int x) { throw x; }

namespace {

const char *tetgen_reason(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen hit an internal error";
    case 3: return "TetGen found a self-intersection in the input surface (sponge facets cross "
                   "each other or a box face)";
    case 4: return "TetGen found an input feature smaller than its tolerance (nearly coincident "
                   "vertices or a vertex almost on a facet)";
    case 5: return "TetGen found two input facets very close to each other";
    case 10: return "TetGen rejected the input (invalid PLC)";
    default: return "TetGen failed";
  }
}

void fill_input(const tg_plc *p, tetgenio &in) {
  in.firstnumber = 0;
  in.numberofpoints = p->npoints;
  in.pointlist = new REAL[3 * (size_t)p->npoints];
  std::memcpy(in.pointlist, p->xyz, 3 * (size_t)p->npoints * sizeof(double));
  if (p->size) {
    in.numberofpointmtrs = 1;
    in.pointmtrlist = new REAL[(size_t)p->npoints];
    std::memcpy(in.pointmtrlist, p->size, (size_t)p->npoints * sizeof(double));
  }
  in.numberoffacets = p->nfacets;
  in.facetlist = new tetgenio::facet[(size_t)p->nfacets];
  for (int f = 0; f < p->nfacets; f++) tetgenio::init(&in.facetlist[f]);
  in.facetmarkerlist = new int[(size_t)p->nfacets];
  for (int f = 0; f < p->nfacets; f++) {
    tetgenio::facet &fc = in.facetlist[f];
    in.facetmarkerlist[f] = p->facet_marker[f];
    int np = p->facet_poly[f + 1] - p->facet_poly[f];
    fc.polygonlist = new tetgenio::polygon[(size_t)np];
    fc.numberofpolygons = np;
    for (int q = 0; q < np; q++) tetgenio::init(&fc.polygonlist[q]);
    for (int q = 0; q < np; q++) {
      int pg = p->facet_poly[f] + q, nv = p->poly_vert[pg + 1] - p->poly_vert[pg];
      fc.polygonlist[q].vertexlist = new int[(size_t)nv];
      fc.polygonlist[q].numberofvertices = nv;
      std::memcpy(fc.polygonlist[q].vertexlist, p->verts + p->poly_vert[pg], (size_t)nv * sizeof(int));
    }
    int nh = p->facet_hole[f + 1] - p->facet_hole[f];
    if (nh > 0) {
      fc.holelist = new REAL[3 * (size_t)nh];
      fc.numberofholes = nh;
      std::memcpy(fc.holelist, p->fholes + 3 * (size_t)p->facet_hole[f], 3 * (size_t)nh * sizeof(double));
    }
  }
  if (p->nholes > 0) {
    in.numberofholes = p->nholes;
    in.holelist = new REAL[3 * (size_t)p->nholes];
    std::memcpy(in.holelist, p->holes, 3 * (size_t)p->nholes * sizeof(double));
  }
}

template <typename T> T *copy_out(const T *src, size_t n) {
  T *d = static_cast<T *>(std::malloc(n ? n * sizeof(T) : 1));
  if (d && n) std::memcpy(d, src, n * sizeof(T));
  return d;
}

}  // namespace

extern "C" {
int tg_fault_inject = 0;
}

extern "C" void tg_result_free(tg_result *r) {
  if (!r) return;
  std::free(r->xyz);
  std::free(r->tet);
  std::free(r->face);
  std::free(r->face_marker);
  std::memset(r, 0, sizeof *r);
}

// TetGen in this process: the call and the copies, every exception caught.
static int run_here(const tg_plc *plc, const char *switches, tg_result *out, char *msg, size_t msglen) {
  std::memset(out, 0, sizeof *out);
  if (msglen) msg[0] = '\0';
  int code = 0;
  try {
    tetgenio in, res;
    fill_input(plc, in);
    if (tg_fault_inject == TG_FAULT_BAD_ALLOC) throw std::bad_alloc();
    if (tg_fault_inject == TG_FAULT_ABORT) std::abort(); /* as a failed assert() in TetGen */
    if (tg_fault_inject) throw int(tg_fault_inject);
    std::vector<char> sw(switches, switches + std::strlen(switches) + 1);
    tetrahedralize(sw.data(), &in, &res);
    if (res.numberofcorners != 4 || !res.tetrahedronlist || !res.trifacelist ||
        !res.trifacemarkerlist) {
      std::snprintf(msg, msglen, "TetGen returned no tetrahedra, boundary faces or face markers "
                                 "(switches '%s')", switches);
      return -1;
    }
    out->npoints = res.numberofpoints;
    out->ntets = res.numberoftetrahedra;
    out->nfaces = res.numberoftrifaces;
    out->xyz = copy_out(res.pointlist, 3 * (size_t)res.numberofpoints);
    out->tet = copy_out(res.tetrahedronlist, 4 * (size_t)res.numberoftetrahedra);
    out->face = copy_out(res.trifacelist, 3 * (size_t)res.numberoftrifaces);
    out->face_marker = copy_out(res.trifacemarkerlist, (size_t)res.numberoftrifaces);
    if (!out->xyz || !out->tet || !out->face || !out->face_marker) {
      tg_result_free(out);
      std::snprintf(msg, msglen, "out of host memory copying TetGen's mesh");
      return -2;
    }
    return 0;
  } catch (int e) {
    code = e;
    std::snprintf(msg, msglen, "%s (TetGen error code %d)", tetgen_reason(e), e);
  } catch (const std::bad_alloc &) {
    code = 1;
    std::snprintf(msg, msglen, "%s (std::bad_alloc)", tetgen_reason(1));
  } catch (...) {
    code = -1;
    std::snprintf(msg, msglen, "TetGen threw an unexpected exception");
  }
  tg_result_free(out);
  return code ? code : -1;
}

// --- TetGen in a worker process ---------------------------------------------
// Debian's libtet keeps TetGen's assert()s, and some inputs trip one (flip41's
// `scount == 1` re-tetrahedralising a hull in a rock run at max_move 0.025):
// abort() would end the whole run, its last step lost and a resume stuck at
// the same step.  So TetGen runs in a worker process, forked at the first
// call and kept (a fork per call cost 7 ms on lavapipe, whose mappings the
// fork copies: +14 % on the rock run); requests and meshes go through a
// socket.  A worker that dies is reported as code -3 with its last line of
// stderr (the assertion), the caller goes on as for any failure of TetGen on
// its input, and the next call forks a new worker.  The worker ignores SIGINT
// and SIGTERM (a stop the run asked for must not become a TetGen failure that
// changes the run's bytes), keeps only its socket and stderr pipe open (no
// run lock), and ends when this process closes the socket.  Calls are
// serialised by a mutex.
namespace {

bool put(int fd, const void *buf, size_t n) {
  const char *p = static_cast<const char *>(buf);
  while (n) {
    ssize_t w = send(fd, p, n, MSG_NOSIGNAL);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w, n -= (size_t)w;
  }
  return true;
}

bool get(int fd, void *buf, size_t n) {
  char *p = static_cast<char *>(buf);
  while (n) {
    ssize_t r = read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r, n -= (size_t)r;
  }
  return true;
}

template <typename T> bool put_n(int fd, const T *a, size_t n) { return !n || put(fd, a, n * sizeof(T)); }
template <typename T> bool get_n(int fd, std::vector<T> &v, size_t n) {
  v.resize(n);
  return !n || get(fd, v.data(), n * sizeof(T));
}

struct request {
  int fault, npoints, has_size, nfacets, nholes;
  char switches[64];
};
struct reply {
  int code, npoints, ntets, nfaces;
  char msg[256];
};

bool send_request(int fd, const tg_plc *p, const char *switches) {
  request q;
  std::memset(&q, 0, sizeof q);
  q.fault = tg_fault_inject, q.npoints = p->npoints, q.has_size = p->size != nullptr, q.nfacets = p->nfacets;
  q.nholes = p->nholes;
  std::snprintf(q.switches, sizeof q.switches, "%s", switches);
  size_t np = (size_t)p->npoints, nf = (size_t)p->nfacets, npoly = (size_t)p->facet_poly[nf];
  size_t nv = (size_t)p->poly_vert[npoly], nfh = (size_t)p->facet_hole[nf];
  return put(fd, &q, sizeof q) && put_n(fd, p->xyz, 3 * np) && (!q.has_size || put_n(fd, p->size, np)) &&
         put_n(fd, p->facet_poly, nf + 1) && put_n(fd, p->poly_vert, npoly + 1) && put_n(fd, p->verts, nv) &&
         put_n(fd, p->facet_hole, nf + 1) && put_n(fd, p->fholes, 3 * nfh) && put_n(fd, p->facet_marker, nf) &&
         put_n(fd, p->holes, 3 * (size_t)p->nholes);
}

// The worker: reads requests until the socket closes.
[[noreturn]] void serve(int fd) {
  for (;;) {
    request q;
    if (!get(fd, &q, sizeof q)) _exit(0);
    q.switches[sizeof q.switches - 1] = '\0';
    std::vector<double> xyz, size, fholes, holes;
    std::vector<int> facet_poly, poly_vert, verts, facet_hole, marker;
    size_t np = (size_t)q.npoints, nf = (size_t)q.nfacets;
    bool ok = get_n(fd, xyz, 3 * np) && (!q.has_size || get_n(fd, size, np)) && get_n(fd, facet_poly, nf + 1);
    ok = ok && get_n(fd, poly_vert, (size_t)facet_poly[nf] + 1) && get_n(fd, verts, (size_t)poly_vert[(size_t)facet_poly[nf]]);
    ok = ok && get_n(fd, facet_hole, nf + 1) && get_n(fd, fholes, 3 * (size_t)facet_hole[nf]) && get_n(fd, marker, nf);
    ok = ok && get_n(fd, holes, 3 * (size_t)q.nholes);
    if (!ok) _exit(0);
    tg_plc p = {q.npoints, xyz.data(), q.has_size ? size.data() : nullptr, q.nfacets, facet_poly.data(),
                poly_vert.data(), verts.data(), facet_hole.data(), fholes.data(), marker.data(), q.nholes,
                holes.data()};
    tg_fault_inject = q.fault;
    tg_result r;
    reply w;
    std::memset(&w, 0, sizeof w);
    w.code = run_here(&p, q.switches, &r, w.msg, sizeof w.msg);
    w.npoints = r.npoints, w.ntets = r.ntets, w.nfaces = r.nfaces;
    ok = put(fd, &w, sizeof w);
    if (ok && w.code == 0)
      ok = put_n(fd, r.xyz, 3 * (size_t)r.npoints) && put_n(fd, r.tet, 4 * (size_t)r.ntets) &&
           put_n(fd, r.face, 3 * (size_t)r.nfaces) && put_n(fd, r.face_marker, (size_t)r.nfaces);
    tg_result_free(&r);
    if (!ok) _exit(0);
  }
}

// Reads a reply into out; false if the worker's answer is incomplete, or
// (*nomem set) if there was no memory to take it.
bool receive(int fd, tg_result *out, reply *w, bool *nomem) {
  if (!get(fd, w, sizeof *w)) return false;
  w->msg[sizeof w->msg - 1] = '\0';
  if (w->code != 0) return true;
  if (w->npoints < 0 || w->ntets < 0 || w->nfaces < 0) return false;
  out->npoints = w->npoints, out->ntets = w->ntets, out->nfaces = w->nfaces;
  out->xyz = static_cast<double *>(std::malloc(3 * (size_t)w->npoints * sizeof(double) + 1));
  out->tet = static_cast<int *>(std::malloc(4 * (size_t)w->ntets * sizeof(int) + 1));
  out->face = static_cast<int *>(std::malloc(3 * (size_t)w->nfaces * sizeof(int) + 1));
  out->face_marker = static_cast<int *>(std::malloc((size_t)w->nfaces * sizeof(int) + 1));
  if (!out->xyz || !out->tet || !out->face || !out->face_marker) {
    *nomem = true;
    return false;
  }
  return get(fd, out->xyz, 3 * (size_t)w->npoints * sizeof(double)) &&
         get(fd, out->tet, 4 * (size_t)w->ntets * sizeof(int)) &&
         get(fd, out->face, 3 * (size_t)w->nfaces * sizeof(int)) &&
         get(fd, out->face_marker, (size_t)w->nfaces * sizeof(int));
}

std::mutex mu;
pid_t worker = 0;
int sock = -1, errfd = -1; // this process's ends
char errline[512];         // the worker's last line of stderr

// Reads what the worker wrote to stderr (non-blocking), keeping the last line.
void drain_stderr() {
  char buf[1024];
  for (;;) {
    ssize_t r = read(errfd, buf, sizeof buf - 1);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return;
    buf[r] = '\0';
    for (char *line = std::strtok(buf, "\n"); line; line = std::strtok(nullptr, "\n"))
      std::snprintf(errline, sizeof errline, "%s", line);
  }
}

// Ends the worker (gone or to be replaced); its exit status in *status.
void worker_end(int *status) {
  if (sock >= 0) close(sock);
  sock = -1;
  *status = 0;
  if (worker > 0)
    while (waitpid(worker, status, 0) < 0 && errno == EINTR) {
    }
  worker = 0;
  if (errfd >= 0) {
    drain_stderr();
    close(errfd);
  }
  errfd = -1;
}

bool worker_start() {
  int sv[2], ep[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) return false;
  if (pipe2(ep, O_CLOEXEC) != 0) {
    close(sv[0]), close(sv[1]);
    return false;
  }
  std::fflush(nullptr); /* nothing buffered is written twice */
  pid_t pid = fork();
  if (pid < 0) {
    close(sv[0]), close(sv[1]), close(ep[0]), close(ep[1]);
    return false;
  }
  if (pid == 0) {
    std::signal(SIGINT, SIG_IGN);
    std::signal(SIGTERM, SIG_IGN);
    dup2(ep[1], 1), dup2(ep[1], 2); /* TetGen's prints and an assertion's message */
    int fd = dup2(sv[1], 3) == 3 ? 3 : -1;
    if (fd < 0) _exit(0);
    closefrom(4); /* the run's lock and every other file stay the parent's */
    serve(fd);
  }
  close(sv[1]), close(ep[1]);
  fcntl(ep[0], F_SETFL, fcntl(ep[0], F_GETFL) | O_NONBLOCK);
  worker = pid, sock = sv[0], errfd = ep[0], errline[0] = '\0';
  return true;
}

}  // namespace

extern "C" int tg_tetrahedralize(const tg_plc *plc, const char *switches, tg_result *out, char *msg,
                                 size_t msglen) {
  std::lock_guard<std::mutex> lock(mu);
  std::memset(out, 0, sizeof *out);
  if (msglen) msg[0] = '\0';
  if (std::strlen(switches) >= sizeof(request{}.switches) || (!worker && !worker_start()))
    return run_here(plc, switches, out, msg, msglen); /* no worker to be had: in this process */
  reply w;
  std::memset(&w, 0, sizeof w);
  bool nomem = false;
  if (send_request(sock, plc, switches) && receive(sock, out, &w, &nomem)) {
    drain_stderr();
    std::snprintf(msg, msglen, "%s", w.msg);
    if (w.code != 0) tg_result_free(out);
    return w.code;
  }
  tg_result_free(out);
  int status = 0;
  worker_end(&status); /* the next call forks a new one */
  if (nomem) { /* ours, not TetGen's: the reply's rest was unread, so the worker went too */
    std::snprintf(msg, msglen, "out of host memory receiving TetGen's mesh");
    return -2;
  }
  if (WIFSIGNALED(status))
    std::snprintf(msg, msglen, "TetGen stopped on signal %d (%s)%s%s", WTERMSIG(status), strsignal(WTERMSIG(status)),
                  errline[0] ? ": " : "", errline);
  else
    std::snprintf(msg, msglen, "TetGen's process ended without its mesh (exit %d)%s%s",
                  WIFEXITED(status) ? WEXITSTATUS(status) : -1, errline[0] ? ": " : "", errline);
  return -3;
}
