/* sessile io — atomic files and mkdir -p.
 *
 * A run directory is read while a run goes on (ParaView reloading the series,
 * a script watching manifest.json), runs get killed, and run directories may
 * be shared.  So no file is ever written in place: data goes to a temporary
 * ".<name>.sessile-tmp.XXXXXXXX" in the same folder (same file system, so the
 * rename is atomic), created with O_CREAT|O_EXCL|O_NOFOLLOW under a random
 * suffix (a planted symlink or file at any name is never opened: we pick
 * another name), fsync'ed, renamed over path, and the folder is fsync'ed.  A
 * reader sees the old file or the new one, never half of one; an error
 * removes the temporary.  Leftovers of a killed process are recognised by
 * sessile_is_temp_name() and removed by the run framework at the next start. */
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>
#include "io_internal.h"

#define TEMP_TAG ".sessile-tmp."

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
  if (af->dirfd >= 0) close(af->dirfd);
  af->dirfd = -1;
}

int sessile_is_temp_name(const char *name) {
  return name[0] == '.' && strstr(name, TEMP_TAG) != NULL;
}

/* Splits path into its folder (opened, following the user's own prefix) and
 * its last component. */
static int open_parent(const char *path, const char **base) {
  const char *slash = strrchr(path, '/');
  *base = slash ? slash + 1 : path;
  if (!slash) return open(".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (slash == path) return open("/", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  char *dir = malloc((size_t)(slash - path) + 1);
  if (!dir) {
    errno = ENOMEM;
    return -1;
  }
  memcpy(dir, path, (size_t)(slash - path));
  dir[slash - path] = 0;
  int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  int e = errno;
  free(dir);
  errno = e;
  return fd;
}

sessile_status sessile_atomic_open(const char *path, sessile_atomic_file *af) {
  af->f = NULL;
  af->path = af->tmp = NULL;
  af->dirfd = -1;
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a file with an empty name");
  const char *base = NULL;
  af->dirfd = open_parent(path, &base);
  if (af->dirfd < 0) {
    int e = errno;
    af_release(af);
    return sessile_error_set(e == ENOMEM ? SESSILE_ERR_NO_MEMORY : SESSILE_ERR_IO,
                             "cannot open the folder of '%s': %s", path, strerror(e));
  }
  SESSILE_CHECK(*base && strcmp(base, ".") && strcmp(base, ".."), SESSILE_ERR_USAGE,
                "cannot write '%s': not a file name", path);
  size_t n = strlen(base) + sizeof TEMP_TAG + 24;
  af->path = dup_str(path);
  af->tmp = malloc(n);
  if (!af->path || !af->tmp) {
    af_release(af);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory opening '%s'", path);
  }
  int fd = -1, e = 0;
  for (int attempt = 0; attempt < 64 && fd < 0; attempt++) {
    uint64_t rnd = 0;
    if (getrandom(&rnd, sizeof rnd, 0) != (ssize_t)sizeof rnd) {
      /* no entropy source: still unique per process and attempt */
      rnd = ((uint64_t)getpid() << 32) ^ (uint64_t)(uintptr_t)af ^ (uint64_t)attempt * 0x9E3779B97F4A7C15ull;
    }
    snprintf(af->tmp, n, ".%s" TEMP_TAG "%016llx", base, (unsigned long long)rnd);
    fd = openat(af->dirfd, af->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    e = errno;
    if (fd < 0 && e != EEXIST) break;
  }
  if (fd < 0) {
    sessile_error_set(SESSILE_ERR_IO,
                      "cannot create '%s' (writing through a temporary in its folder): %s", path,
                      strerror(e));
    af_release(af);
    return SESSILE_ERR_IO;
  }
  af->f = fdopen(fd, "wb");
  if (!af->f) {
    e = errno;
    close(fd);
    unlinkat(af->dirfd, af->tmp, 0);
    af_release(af);
    return sessile_error_set(SESSILE_ERR_IO, "cannot open a stream for '%s': %s", path, strerror(e));
  }
  return SESSILE_OK;
}

void sessile_atomic_abort(sessile_atomic_file *af) {
  if (!af) return;
  if (af->f) fclose(af->f);
  if (af->tmp && af->dirfd >= 0) unlinkat(af->dirfd, af->tmp, 0);
  af_release(af);
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
  const char *base = strrchr(af->path, '/');
  base = base ? base + 1 : af->path;
  /* renameat replaces a symlink planted at the final name, never its target */
  if (!what && renameat(af->dirfd, af->tmp, af->dirfd, base) != 0) what = "rename into place", e = errno;
  if (what) {
    sessile_status s = sessile_error_set(SESSILE_ERR_IO, "cannot %s '%s': %s", what, af->path,
                                         strerror(e));
    unlinkat(af->dirfd, af->tmp, 0);
    af_release(af);
    return s;
  }
  /* fsync the folder so the rename itself survives a crash; file systems
   * that cannot sync a directory (EINVAL) are not an error. */
  sessile_status s = SESSILE_OK;
  if (fsync(af->dirfd) != 0 && errno != EINVAL)
    s = sessile_error_set(SESSILE_ERR_IO, "cannot sync the folder of '%s': %s", af->path, strerror(errno));
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
