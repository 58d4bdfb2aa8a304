/* The readers' input: a regular file opened without blocking, read in
 * fixed chunks so that memory does not grow with the file and a wrong
 * header is found in the first chunk. */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "io_internal.h"

sessile_status io_open_regular(const char *path, const char *what, int *fd, uint64_t *size) {
  *fd = -1, *size = 0;
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "no %s file given", what);
  int f = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  SESSILE_CHECK(f >= 0, SESSILE_ERR_USAGE, "cannot open the %s '%.200s': %s", what, path, strerror(errno));
  struct stat st;
  if (fstat(f, &st) != 0 || !S_ISREG(st.st_mode)) {
    close(f);
    return sessile_error_set(SESSILE_ERR_USAGE, "the %s '%.200s' is not a regular file", what, path);
  }
  *fd = f, *size = (uint64_t)st.st_size;
  return SESSILE_OK;
}

sessile_status io_in_open(io_in *r, const char *path, const char *what) {
  r->path = path, r->off = 0, r->line = 1, r->at = r->n = 0;
  return io_open_regular(path, what, &r->fd, &r->size);
}

void io_in_close(io_in *r) {
  if (r->fd >= 0) close(r->fd);
  r->fd = -1;
}

sessile_status io_in_more(io_in *r, size_t *avail) {
  if (r->at == r->n) {
    r->at = r->n = 0;
    ssize_t k;
    do k = read(r->fd, r->buf, sizeof r->buf);
    while (k < 0 && errno == EINTR);
    SESSILE_CHECK(k >= 0, SESSILE_ERR_IO, "%s: read failed: %s", r->path, strerror(errno));
    r->n = (size_t)k;
  }
  *avail = r->n - r->at;
  return SESSILE_OK;
}

/* Consumes up to and including the next newline, copying at most room
 * bytes to dst; *took the line's bytes consumed, *ended whether a newline
 * (or the file's end) was reached. */
static sessile_status take_line(io_in *r, char *dst, size_t room, size_t *took, int *ended, int *got) {
  size_t k = 0, avail;
  *ended = 0, *got = 0;
  for (;;) {
    SESSILE_CALL(io_in_more(r, &avail));
    if (!avail) {
      *ended = 1;
      break;
    }
    *got = 1;
    const unsigned char *p = r->buf + r->at;
    const unsigned char *nl = memchr(p, '\n', avail);
    size_t take = nl ? (size_t)(nl - p) : avail;
    if (dst && take > room - k) take = room - k, nl = NULL; /* the line is longer than room */
    SESSILE_CHECK(!memchr(p, 0, take), SESSILE_ERR_USAGE, "%s: line %llu holds a NUL byte (not a text file)",
                  r->path, (unsigned long long)r->line);
    if (dst) memcpy(dst + k, p, take);
    k += take;
    r->at += take + (nl != NULL), r->off += take + (nl != NULL);
    if (nl) {
      *ended = 1;
      break;
    }
    if (dst && k == room) break;
  }
  if (*got && *ended) r->line++;
  *took = k;
  return SESSILE_OK;
}

sessile_status io_in_line(io_in *r, char *line, size_t cap, size_t *len, int *got) {
  size_t k = 0;
  int ended;
  SESSILE_CALL(take_line(r, line, cap - 1, &k, &ended, got));
  if (!ended) {
    line[k] = 0;
    *len = cap;
    return SESSILE_OK;
  }
  if (k > 0 && line[k - 1] == '\r') k--;
  line[k] = 0;
  *len = k;
  return SESSILE_OK;
}

sessile_status io_in_skip_line(io_in *r) {
  size_t k = 0;
  int ended, got;
  return take_line(r, NULL, 0, &k, &ended, &got);
}

sessile_status io_in_bytes(io_in *r, void *dst, size_t n, int *got) {
  unsigned char *d = dst;
  *got = 0;
  while (n) {
    size_t avail;
    SESSILE_CALL(io_in_more(r, &avail));
    if (!avail) return SESSILE_OK;
    size_t take = avail < n ? avail : n;
    memcpy(d, r->buf + r->at, take);
    d += take, n -= take, r->at += take, r->off += take;
  }
  *got = 1;
  return SESSILE_OK;
}
