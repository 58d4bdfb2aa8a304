/* Append-only logs of a run (sessile_run_log): files such as sds/steps.csv
 * that grow by rows as the run goes, too large to rewrite atomically at each
 * frame.  A checkpoint keeps each log's length, and a resume cuts what was
 * appended after it, so that a resumed run's log has each row once, as
 * records.jsonl does (docs/run.md). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "run_internal.h"

static int find(const run_log_len *logs, int n, const char *rel) {
  for (int i = 0; i < n; i++)
    if (!strcmp(logs[i].rel, rel)) return i;
  return -1;
}

int run_open_cut(int dfd, const char *name, uint64_t keep, int refuse_short, const char **why) {
  int fd = openat(dfd, name, O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
  if (fd < 0) {
    *why = errno == ELOOP   ? "a symlink is there: refused"
           : errno == ENXIO ? "not a regular file: a FIFO or device is there"
                            : strerror(errno);
    return -1;
  }
  struct stat st;
  *why = NULL;
  if (fstat(fd, &st) != 0) *why = strerror(errno);
  else if (!S_ISREG(st.st_mode)) *why = "not a regular file";
  else if (refuse_short && (uint64_t)st.st_size < keep) *why = "shorter than the checkpoint says (cut or replaced since)";
  else if (ftruncate(fd, (off_t)keep) != 0) *why = strerror(errno);
  else {
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, (fl | O_APPEND) & ~O_NONBLOCK) != 0) *why = strerror(errno);
  }
  if (*why) {
    close(fd);
    return -1;
  }
  return fd;
}

/* Opens rel (listed, its folder made by sessile_run_file) for appending, cut
 * to `keep` bytes; no symlink is followed, in the folder or at the file, and
 * only a regular file is taken (O_NONBLOCK: a planted FIFO does not hang). */
static sessile_status open_log(sessile_run *r, const char *rel, uint64_t keep, int *fd_out) {
  char path[4096];
  SESSILE_CALL(sessile_run_file(r, rel, path, sizeof path));
  const char *slash = strchr(rel, '/');
  int dfd = r->dfd, sfd = -1;
  if (slash) {
    char sub[RUN_LOG_NAME];
    snprintf(sub, sizeof sub, "%.*s", (int)(slash - rel), rel);
    sfd = openat(r->dfd, sub, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    SESSILE_CHECK(sfd >= 0, SESSILE_ERR_IO, "cannot open the folder of '%s': %s", path, strerror(errno));
    dfd = sfd;
  }
  const char *name = slash ? slash + 1 : rel;
  const char *why = NULL;
  int fd = run_open_cut(dfd, name, keep, 1, &why);
  if (sfd >= 0) close(sfd);
  SESSILE_CHECK(fd >= 0, SESSILE_ERR_IO, "cannot append to '%s': %s", path, why);
  *fd_out = fd;
  return SESSILE_OK;
}

sessile_status sessile_run_log(sessile_run *r, const char *rel, const void *bytes, size_t n) {
  SESSILE_CHECK(r && rel && (bytes || !n), SESSILE_ERR_INTERNAL, "sessile_run_log: no run, name or bytes");
  SESSILE_CHECK(strlen(rel) < RUN_LOG_NAME, SESSILE_ERR_INTERNAL, "run log name '%.40s...' is too long", rel);
  int k = find(r->logs, r->nlogs, rel);
  if (k < 0) {
    SESSILE_CHECK(r->nlogs < RUN_MAX_LOGS, SESSILE_ERR_INTERNAL, "a run keeps at most %d logs ('%s')", RUN_MAX_LOGS,
                  rel);
    /* a resume continues from the checkpoint's length; a new run (or one
     * killed before its first checkpoint) from nothing */
    int c = r->ckpt ? find(r->ckpt->logs, r->ckpt->nlogs, rel) : -1;
    uint64_t keep = c >= 0 ? r->ckpt->logs[c].bytes : 0;
    int fd;
    SESSILE_CALL(open_log(r, rel, keep, &fd));
    k = r->nlogs++;
    r->log_fd[k] = fd;
    snprintf(r->logs[k].rel, sizeof r->logs[k].rel, "%s", rel);
    r->logs[k].bytes = keep;
  }
  const char *p = bytes;
  size_t done = 0;
  while (done < n) {
    ssize_t w = write(r->log_fd[k], p + done, n - done);
    if (w < 0 && errno == EINTR) continue;
    SESSILE_CHECK(w >= 0, SESSILE_ERR_IO, "cannot append to '%s/%s': %s", r->dir, rel, strerror(errno));
    done += (size_t)w;
  }
  r->logs[k].bytes += n;
  return SESSILE_OK;
}

void run_logs_to_keep(const sessile_run *r, run_log_len *out, int *n) {
  int m = 0;
  for (int i = 0; i < r->nlogs; i++) out[m++] = r->logs[i];
  for (int i = 0; r->ckpt && i < r->ckpt->nlogs; i++)
    if (find(r->logs, r->nlogs, r->ckpt->logs[i].rel) < 0 && m < RUN_MAX_LOGS) out[m++] = r->ckpt->logs[i];
  *n = m;
}

void run_logs_sync(const sessile_run *r) {
  for (int i = 0; i < r->nlogs; i++) fdatasync(r->log_fd[i]);
}

void run_logs_close(sessile_run *r) {
  for (int i = 0; i < r->nlogs; i++) fsync(r->log_fd[i]), close(r->log_fd[i]);
  r->nlogs = 0;
}
