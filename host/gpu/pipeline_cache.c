/* On-disk VkPipelineCache: lavapipe compiles every pipeline through LLVM
 * (tens of ms each), so reusing compiled pipelines across runs matters.  The
 * file is keyed by vendor, device and pipelineCacheUUID.  A cache that cannot
 * be read or written is not an error: we only lose speed, and say nothing.
 *
 * The cache folder may be shared or tampered with, so nothing in it is
 * trusted beyond "a regular file of ours":
 *   - missing folders are created with mode 0700; the default folder
 *     (the caller's cache_default: the CLI's $XDG_CACHE_HOME/sessile or
 *     ~/.cache/sessile) is not used when it is a
 *     symlink (an explicit cache_dir is the caller's choice: it is resolved
 *     once with realpath);
 *   - the folder and the file must belong to us (euid);
 *   - the file is opened with O_NOFOLLOW | O_NONBLOCK (a planted symlink is
 *     refused, a FIFO does not block) and used only when fstat says it is a
 *     regular file of 1 byte .. 256 MiB;
 *   - it is written through a new file (O_CREAT | O_EXCL | O_NOFOLLOW, mode
 *     0600) with an unpredictable name in the same folder,
 *     ".<name>.sessile-tmp.<12 random chars>", then fsync, rename over the
 *     cache file (which replaces a planted symlink or FIFO rather than
 *     writing through it) and fsync of the folder.
 * Every file operation is relative to a descriptor of the folder opened with
 * O_NOFOLLOW, so the folder cannot be swapped for a symlink between the
 * checks and the use.  Paths have no fixed-size buffers: a cache path that
 * does not fit g->cache_path turns the cache off instead of being cut. */
#define _DEFAULT_SOURCE /* realpath; getrandom */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>
#include "gpu_internal.h"

enum { CACHE_MAX_BYTES = 256 << 20, TMP_RANDOM = 12, TMP_TRIES = 16 };

/* malloc'd printf; NULL when out of memory. */
static char *str_printf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static char *str_printf(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0) return NULL;
  char *s = malloc((size_t)n + 1);
  if (!s) return NULL;
  va_start(ap, fmt);
  vsnprintf(s, (size_t)n + 1, fmt, ap);
  va_end(ap);
  return s;
}

/* mkdir -p; what it creates gets mode 0700.  0 when every step worked. */
static int mkdirs(const char *path) {
  char *tmp = strdup(path);
  if (!tmp) return -1;
  int rc = 0;
  for (char *p = tmp + 1; *p && rc == 0; p++) {
    if (*p != '/') continue;
    *p = 0;
    if (mkdir(tmp, 0700) != 0 && errno != EEXIST) rc = -1;
    *p = '/';
  }
  if (rc == 0 && mkdir(tmp, 0700) != 0 && errno != EEXIST) rc = -1;
  free(tmp);
  return rc;
}

/* Opens folder dir without following a symlink as its last component; -1
 * unless it is a folder owned by us. */
static int open_dir_checked(const char *dir) {
  int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return -1;
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != geteuid()) {
    close(fd);
    return -1;
  }
  return fd;
}

/* Splits g->cache_path into a descriptor of its folder and its file name
 * (pointing into cache_path); -1 when the folder is unusable. */
static int open_cache_dir(const char *cache_path, const char **name) {
  const char *slash = strrchr(cache_path, '/');
  if (!slash || !slash[1] || slash == cache_path) return -1;
  char *dir = strndup(cache_path, (size_t)(slash - cache_path));
  if (!dir) return -1;
  int fd = open_dir_checked(dir);
  free(dir);
  *name = slash + 1;
  return fd;
}

/* Sets g->cache_path, or leaves it "" when the cache is off or unusable. */
static void cache_path(sessile_gpu *g, const char *dir, const char *default_dir) {
  g->cache_path[0] = 0;
  if (dir && !*dir) return; /* disabled */
  char *base = NULL;
  if (dir) {
    /* the caller's folder: create it, then use its real location */
    if (mkdirs(dir) != 0) return;
    base = realpath(dir, NULL);
  } else if (default_dir && *default_dir) {
    base = strdup(default_dir);
  }
  if (!base) return;
  if (!dir && mkdirs(base) != 0) {
    free(base);
    return;
  }
  int dfd = open_dir_checked(base); /* a symlink or another user's folder: no cache */
  if (dfd < 0) {
    free(base);
    return;
  }
  close(dfd);
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(g->phys, &p);
  char uuid[2 * VK_UUID_SIZE + 1];
  for (unsigned i = 0; i < VK_UUID_SIZE; i++) snprintf(uuid + 2 * i, 3, "%02x", p.pipelineCacheUUID[i]);
  int n = snprintf(g->cache_path, sizeof g->cache_path, "%s/pipelines-%04x-%04x-%s.bin", base,
                   p.vendorID, p.deviceID, uuid);
  if (n < 0 || (size_t)n >= sizeof g->cache_path) g->cache_path[0] = 0; /* too long: off, not cut */
  free(base);
}

/* Reads the cache file into *data (malloc'd); 0 bytes when there is none
 * or it is anything but a regular file of ours of sane size. */
static size_t read_cache(const char *cache_path, void **data) {
  *data = NULL;
  const char *name;
  int dfd = open_cache_dir(cache_path, &name);
  if (dfd < 0) return 0;
  int fd = openat(dfd, name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  close(dfd);
  if (fd < 0) return 0;
  struct stat st;
  size_t size = 0;
  if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == geteuid() && st.st_size > 0 &&
      st.st_size < CACHE_MAX_BYTES && (*data = malloc((size_t)st.st_size)) != NULL) {
    size_t want = (size_t)st.st_size;
    while (size < want) {
      ssize_t r = read(fd, (char *)*data + size, want - size);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) break;
      size += (size_t)r;
    }
    if (size != want) { /* changed under us: ignore it */
      free(*data);
      *data = NULL;
      size = 0;
    }
  }
  close(fd);
  return size;
}

/* TMP_RANDOM characters from [A-Za-z0-9] drawn from the kernel's generator. */
static int random_name(char *out) {
  static const char set[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  unsigned char r[TMP_RANDOM];
  size_t got = 0;
  while (got < sizeof r) {
    ssize_t n = getrandom(r + got, sizeof r - got, GRND_NONBLOCK); /* never wait at boot */
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += (size_t)n;
  }
  if (got < sizeof r) { /* no getrandom (old kernel, seccomp) or not ready yet: /dev/urandom */
    int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    got = 0;
    while (got < sizeof r) {
      ssize_t n = read(fd, r + got, sizeof r - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += (size_t)n;
    }
    close(fd);
    if (got < sizeof r) return -1;
  }
  for (int i = 0; i < TMP_RANDOM; i++) out[i] = set[r[i] % (sizeof set - 1)];
  out[TMP_RANDOM] = 0;
  return 0;
}

static int write_all(int fd, const void *data, size_t size) {
  size_t done = 0;
  while (done < size) {
    ssize_t w = write(fd, (const char *)data + done, size - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return -1;
    done += (size_t)w;
  }
  return 0;
}

/* Temp file + fsync + rename + folder fsync; any failure leaves the old
 * cache file (or none) and no temporary. */
static void write_cache(const char *cache_path, const void *data, size_t size) {
  const char *name;
  int dfd = open_cache_dir(cache_path, &name);
  if (dfd < 0) return;
  char *tmp = NULL;
  int fd = -1;
  for (int tries = 0; tries < TMP_TRIES && fd < 0; tries++) {
    char rnd[TMP_RANDOM + 1];
    if (random_name(rnd) != 0) break;
    free(tmp);
    tmp = str_printf(".%s.sessile-tmp.%s", name, rnd);
    if (!tmp) break;
    fd = openat(dfd, tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd >= 0) {
    int ok = write_all(fd, data, size) == 0 && fsync(fd) == 0;
    ok = close(fd) == 0 && ok;
    if (ok) ok = renameat(dfd, tmp, dfd, name) == 0;
    if (ok) fsync(dfd); /* best effort: some file systems cannot sync a folder */
    else unlinkat(dfd, tmp, 0);
  }
  free(tmp);
  close(dfd);
}

sessile_status sessile_pipeline_cache_open_(sessile_gpu *g, const char *dir, const char *default_dir) {
  cache_path(g, dir, default_dir);
  void *data = NULL;
  size_t size = g->cache_path[0] ? read_cache(g->cache_path, &data) : 0;
  VkPipelineCacheCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
                                  .initialDataSize = size,
                                  .pInitialData = size ? data : NULL};
  VkResult r = vkCreatePipelineCache(g->device, &ci, NULL, &g->pipeline_cache);
  if (r < 0 && size) { /* the driver rejected stale data: start empty */
    ci.initialDataSize = 0;
    ci.pInitialData = NULL;
    r = vkCreatePipelineCache(g->device, &ci, NULL, &g->pipeline_cache);
  }
  free(data);
  if (r < 0) return sessile_vk_fail_(r, "vkCreatePipelineCache", __func__);
  return SESSILE_OK;
}

void sessile_pipeline_cache_close_(sessile_gpu *g) {
  if (!g->pipeline_cache) return;
  size_t size = 0;
  void *data = NULL;
  if (g->cache_path[0] &&
      vkGetPipelineCacheData(g->device, g->pipeline_cache, &size, NULL) == VK_SUCCESS && size &&
      size < CACHE_MAX_BYTES && (data = malloc(size)) != NULL &&
      vkGetPipelineCacheData(g->device, g->pipeline_cache, &size, data) == VK_SUCCESS)
    write_cache(g->cache_path, data, size);
  free(data);
  vkDestroyPipelineCache(g->device, g->pipeline_cache, NULL);
  g->pipeline_cache = VK_NULL_HANDLE;
}
