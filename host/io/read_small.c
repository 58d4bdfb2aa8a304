/* Reading a small input file whole (a grammar, a model): a regular file of
 * at most `max` bytes.  O_NONBLOCK so that a FIFO or a device named by the
 * user cannot hang the command; fstat then refuses anything but a regular
 * file. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "sessile/io/io.h"

sessile_status sessile_read_small_file(const char *path, size_t max, const char *what, char **text, size_t *len) {
  *text = NULL, *len = 0;
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  SESSILE_CHECK(fd >= 0, SESSILE_ERR_USAGE, "cannot open the %s '%.200s': %s", what, path, strerror(errno));
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || (uint64_t)st.st_size > (uint64_t)max) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_USAGE, "the %s '%.200s' is not a regular file of at most %zu bytes", what,
                             path, max);
  }
  char *t = malloc((size_t)st.st_size + 1);
  if (!t) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the %s '%.200s'", what, path);
  }
  size_t n = 0;
  for (ssize_t k; n < (size_t)st.st_size && (k = read(fd, t + n, (size_t)st.st_size - n)) > 0;) n += (size_t)k;
  close(fd);
  t[n] = 0;
  *text = t, *len = n;
  return SESSILE_OK;
}

sessile_status sessile_read_small_file_at(int dfd, const char *name, const char *shown, size_t max, char **text,
                                          size_t *len) {
  *text = NULL, *len = 0;
  int fd = openat(dfd, name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0 && errno == ENOENT) return SESSILE_OK;
  SESSILE_CHECK(fd >= 0, SESSILE_ERR_USAGE, "cannot read %s: %s%s", shown, strerror(errno),
                errno == ELOOP ? " (a symlink: refused)" : "");
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || (uint64_t)st.st_size > (uint64_t)max) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_USAGE, "%s is not a regular file of at most %zu bytes", shown, max);
  }
  char *t = malloc((size_t)st.st_size + 1);
  if (!t) {
    close(fd);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory reading %s", shown);
  }
  size_t n = 0;
  while (n < (size_t)st.st_size) {
    ssize_t k = read(fd, t + n, (size_t)st.st_size - n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) break;
    n += (size_t)k;
  }
  close(fd);
  t[n] = 0;
  *text = t, *len = n;
  return SESSILE_OK;
}
