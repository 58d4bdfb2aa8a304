/* sessile io — atomic files and mkdir -p.
 *
 * A run directory is read while a run goes on (ParaView reloading the series,
 * a script watching manifest.json), and runs get killed.  So no file is ever
 * written in place: data goes to "<path>.tmp.<pid>" in the same folder (same
 * file system, so rename is atomic), is flushed and fsync'ed, then renamed
 * over path.  A reader sees the old file or the new one, never half of one;
 * an error removes the temporary. */
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "io_internal.h"

static char *dup_str(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

static void af_release(sessile_atomic_file *af) {
  free(af->path);
  free(af->tmp);
  af->path = af->tmp = NULL;
  af->f = NULL;
}

sessile_status sessile_atomic_open(const char *path, sessile_atomic_file *af) {
  af->f = NULL;
  af->path = af->tmp = NULL;
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a file with an empty name");
  size_t n = strlen(path) + 40;
  af->path = dup_str(path);
  af->tmp = malloc(n);
  if (!af->path || !af->tmp) {
    af_release(af);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory opening '%s'", path);
  }
  snprintf(af->tmp, n, "%s.tmp.%ld", path, (long)getpid());
  int fd = open(af->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    int e = errno;
    sessile_error_set(SESSILE_ERR_IO, "cannot create '%s' (writing through '%s'): %s", path, af->tmp,
                      strerror(e));
    af_release(af);
    return SESSILE_ERR_IO;
  }
  af->f = fdopen(fd, "wb");
  if (!af->f) {
    int e = errno;
    close(fd);
    unlink(af->tmp);
    af_release(af);
    return sessile_error_set(SESSILE_ERR_IO, "cannot open a stream for '%s': %s", path, strerror(e));
  }
  return SESSILE_OK;
}

void sessile_atomic_abort(sessile_atomic_file *af) {
  if (!af) return;
  if (af->f) fclose(af->f);
  if (af->tmp) unlink(af->tmp);
  af_release(af);
}

/* fsync the folder holding path so the rename itself survives a crash; file
 * systems that cannot sync a directory (EINVAL) are not an error. */
static int sync_parent(const char *path) {
  const char *slash = strrchr(path, '/');
  char *dir = NULL;
  if (!slash) dir = dup_str(".");
  else if (slash == path) dir = dup_str("/");
  else {
    dir = malloc((size_t)(slash - path) + 1);
    if (dir) {
      memcpy(dir, path, (size_t)(slash - path));
      dir[slash - path] = 0;
    }
  }
  if (!dir) return ENOMEM;
  int rc = 0, fd = open(dir, O_RDONLY | O_CLOEXEC);
  if (fd >= 0) {
    if (fsync(fd) != 0 && errno != EINVAL) rc = errno;
    close(fd);
  }
  free(dir);
  return rc;
}

sessile_status sessile_atomic_commit(sessile_atomic_file *af) {
  SESSILE_CHECK(af && af->f, SESSILE_ERR_INTERNAL, "commit of a file that is not open");
  const char *what = NULL;
  int e = 0;
  if (ferror(af->f)) what = "write", e = EIO;
  else if (fflush(af->f) != 0) what = "write", e = errno;
  else if (fsync(fileno(af->f)) != 0) what = "sync", e = errno;
  int rc = fclose(af->f);
  af->f = NULL;
  if (!what && rc != 0) what = "close", e = errno;
  if (!what && rename(af->tmp, af->path) != 0) what = "rename into place", e = errno;
  if (what) {
    sessile_status s = sessile_error_set(SESSILE_ERR_IO, "cannot %s '%s': %s", what, af->path,
                                         strerror(e));
    unlink(af->tmp);
    af_release(af);
    return s;
  }
  e = sync_parent(af->path);
  sessile_status s = SESSILE_OK;
  if (e) s = sessile_error_set(SESSILE_ERR_IO, "cannot sync the folder of '%s': %s", af->path, strerror(e));
  af_release(af);
  return s;
}

sessile_status io_write(sessile_atomic_file *af, const void *data, size_t bytes) {
  if (bytes == 0) return SESSILE_OK;
  if (fwrite(data, 1, bytes, af->f) != bytes)
    return sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': %s", af->path, strerror(errno));
  return SESSILE_OK;
}

sessile_status io_printf(sessile_atomic_file *af, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = vfprintf(af->f, fmt, ap);
  va_end(ap);
  if (rc < 0) return sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': %s", af->path, strerror(errno));
  return SESSILE_OK;
}

sessile_status io_xml_escaped(sessile_atomic_file *af, const char *s) {
  for (; *s; s++) {
    const char *r = NULL;
    switch (*s) {
    case '&': r = "&amp;"; break;
    case '<': r = "&lt;"; break;
    case '>': r = "&gt;"; break;
    case '"': r = "&quot;"; break;
    case '\'': r = "&apos;"; break;
    default: break;
    }
    if (r) SESSILE_CALL(io_write(af, r, strlen(r)));
    else SESSILE_CALL(io_write(af, s, 1));
  }
  return SESSILE_OK;
}

sessile_status sessile_write_file_atomic(const char *path, const void *data, size_t bytes) {
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status s = io_write(&af, data, bytes);
  if (s != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return s;
  }
  return sessile_atomic_commit(&af);
}

sessile_status sessile_mkdirs(const char *path) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot create a folder with an empty name");
  char *p = dup_str(path);
  SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of memory creating '%s'", path);
  size_t n = strlen(p);
  while (n > 1 && p[n - 1] == '/') p[--n] = 0;
  /* create each prefix ending before a '/', then the whole path */
  for (size_t i = 1; i <= n; i++) {
    if (i < n && p[i] != '/') continue;
    char c = p[i];
    p[i] = 0;
    if (mkdir(p, 0777) != 0) {
      int e = errno;
      struct stat st;
      if (e != EEXIST || stat(p, &st) != 0 || !S_ISDIR(st.st_mode)) {
        if (e == EEXIST) e = ENOTDIR;
        sessile_status s = sessile_error_set(SESSILE_ERR_IO, "cannot create folder '%s': %s", p, strerror(e));
        free(p);
        return s;
      }
    }
    p[i] = c;
  }
  free(p);
  return SESSILE_OK;
}
