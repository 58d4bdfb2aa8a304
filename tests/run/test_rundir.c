/* The run directory (sessile/run/run.h) without a generator: the lock refuses a
 * second run and names the first; a folder holding a run is refused unless
 * replaced (which removes exactly the listed files) or resumed; a non-run
 * folder is refused; temporaries of a killed run are swept; a symlink
 * planted as a subfolder or at a final name never redirects a write; the
 * checkpoint round-trips and a damaged one is reported; a resume cuts the
 * records and the logs (sessile_run_log) written after its checkpoint, and
 * refuses a log cut shorter than it; a log never follows a symlink or opens
 * a FIFO; the manifest records the states. */
#include <cjson/cJSON.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "sessile/io/io.h"
#include "sessile/run/run.h"
#include "testutil.h"

static char dir[200], path[512];

static sessile_status open_run(sessile_run_mode mode, sessile_run **r) {
  char *argv[] = {"sessile", "test", NULL};
  sessile_run_options o = {.dir = dir, .generator = "test", .version = "t", .argc = 2, .argv = argv, .mode = mode};
  return sessile_run_open(&o, r);
}

static char *slurp(const char *p) {
  FILE *f = fopen(p, "rb");
  if (!f) return NULL;
  char *b = calloc(1, 1 << 20);
  size_t n = b ? fread(b, 1, (1 << 20) - 1, f) : 0;
  (void)n;
  fclose(f);
  return b;
}

static const char *manifest_state(void) {
  static char st[32];
  snprintf(path, sizeof path, "%s/manifest.json", dir);
  char *t = slurp(path);
  cJSON *m = t ? cJSON_Parse(t) : NULL;
  const cJSON *s = cJSON_GetObjectItem(m, "state");
  snprintf(st, sizeof st, "%s", cJSON_IsString(s) ? s->valuestring : "?");
  cJSON_Delete(m);
  free(t);
  return st;
}

static int exists(const char *rel) {
  struct stat st;
  snprintf(path, sizeof path, "%s/%s", dir, rel);
  return lstat(path, &st) == 0;
}

static void write_small(sessile_run *r, const char *rel, const char *text) {
  char p[512];
  t_ok(rel, sessile_run_file(r, rel, p, sizeof p));
  t_ok(rel, sessile_write_file_atomic(p, text, strlen(text)));
}

int main(void) {
  snprintf(dir, sizeof dir, "/tmp/sessile-rundir-XXXXXX");
  t_true("temporary folder", mkdtemp(dir) != NULL);

  sessile_run *r = NULL, *r2 = NULL;
  t_ok("a run opens an empty folder", open_run(SESSILE_RUN_NEW, &r));
  t_true("state running", !strcmp(manifest_state(), "running"));
  t_true("a second run into the locked folder is refused",
         open_run(SESSILE_RUN_NEW, &r2) == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "in use") &&
             strstr(sessile_error_message(), "pid "));
  t_true("even with --force", open_run(SESSILE_RUN_REPLACE, &r2) == SESSILE_ERR_USAGE);
  write_small(r, "a/one.json", "one");
  write_small(r, "top.json", "top");
  cJSON *rec = cJSON_CreateObject();
  cJSON_AddNumberToObject(rec, "iteration", 1);
  t_ok("a record", sessile_run_record(r, rec));
  t_ok("a log's first rows", sessile_run_log(r, "a/log.csv", "h\nrow1\n", 7));
  t_ok("a second log", sessile_run_log(r, "top.csv", "x\n", 2));
  double blob[3] = {1.5, -2.25, 1e300};
  sessile_ckpt_section sec = {"blob", blob, sizeof blob};
  t_ok("a checkpoint", sessile_run_checkpoint(r, 1, 1, &sec));
  cJSON_ReplaceItemInObject(rec, "iteration", cJSON_CreateNumber(2));
  t_ok("a record after the checkpoint", sessile_run_record(r, rec));
  t_ok("a log row after the checkpoint", sessile_run_log(r, "a/log.csv", "row2\n", 5));
  t_ok("set the config", sessile_run_set_config(r, cJSON_CreateString("cfg")));
  sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped");
  t_true("close interrupted", sessile_run_close(r, SESSILE_ERR_INTERRUPTED) == SESSILE_ERR_INTERRUPTED);
  t_true("state interrupted", !strcmp(manifest_state(), "interrupted"));

  /* leftovers of a killed process, and a foreign file the run never listed */
  snprintf(path, sizeof path, "%s/a/.one.json.sessile-tmp.0123456789abcdef", dir);
  FILE *f = fopen(path, "w");
  if (f) fclose(f);
  snprintf(path, sizeof path, "%s/a/mine.txt", dir);
  f = fopen(path, "w");
  if (f) fclose(f);

  t_true("a folder holding a run is refused without --force",
         open_run(SESSILE_RUN_NEW, &r2) == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "--force"));
  t_true("the refused folder keeps its files", exists("a/one.json") && exists("top.json"));

  t_ok("resume opens it", open_run(SESSILE_RUN_RESUME, &r));
  const sessile_ckpt *ck = sessile_run_checkpoint_loaded(r);
  size_t n = 0;
  const double *b = ck ? sessile_ckpt_get(ck, "blob", &n) : NULL;
  t_true("the checkpoint round-trips", ck && sessile_ckpt_iteration(ck) == 1 && b && n == sizeof blob &&
                                         !memcmp(b, blob, sizeof blob));
  t_true("the stored config comes back", cJSON_IsString(sessile_run_config(r)));
  t_true("temporaries were swept", !exists("a/.one.json.sessile-tmp.0123456789abcdef"));
  snprintf(path, sizeof path, "%s/records.jsonl", dir);
  char *recs = slurp(path);
  t_true("records after the checkpoint are cut", recs && !strcmp(recs, "{\"iteration\":1}\n"));
  free(recs);
  t_ok("the log continues", sessile_run_log(r, "a/log.csv", "row2b\n", 6));
  snprintf(path, sizeof path, "%s/a/log.csv", dir);
  char *lg = slurp(path);
  t_true("the log's rows after the checkpoint are cut at its first append", lg && !strcmp(lg, "h\nrow1\nrow2b\n"));
  free(lg);
  t_ok("a checkpoint of the resumed run", sessile_run_checkpoint(r, 2, 1, &sec));
  t_ok("close the resumed run", sessile_run_close(r, SESSILE_OK));
  t_ok("resume it again", open_run(SESSILE_RUN_RESUME, &r));
  snprintf(path, sizeof path, "%s/top.csv", dir);
  t_true("cut a log shorter than the checkpoint says", truncate(path, 0) == 0);
  t_true("... a resume refuses to append to it",
         sessile_run_log(r, "top.csv", "y\n", 2) == SESSILE_ERR_IO && strstr(sessile_error_message(), "shorter"));
  t_ok("and appends to the log the checkpoint kept from the earlier start", sessile_run_log(r, "a/log.csv", "row3\n", 5));
  snprintf(path, sizeof path, "%s/a/log.csv", dir);
  lg = slurp(path);
  t_true("... after its rows", lg && !strcmp(lg, "h\nrow1\nrow2b\nrow3\n"));
  free(lg);
  t_ok("close completed", sessile_run_close(r, SESSILE_OK));
  t_true("state completed", !strcmp(manifest_state(), "completed"));

  t_ok("--force replaces the run", open_run(SESSILE_RUN_REPLACE, &r));
  t_true("--force removed the listed files", !exists("a/one.json") && !exists("top.json") && !exists("a/log.csv"));
  t_true("--force kept a file the run never listed", exists("a/mine.txt"));
  t_true("--force removed the checkpoint", !exists("checkpoint.bin"));

  /* A symlink planted as a subfolder or at a final name. */
  char outside[160];
  snprintf(outside, sizeof outside, "%.120s-outside", dir);
  mkdir(outside, 0700);
  snprintf(path, sizeof path, "%s/victim.txt", outside);
  f = fopen(path, "w");
  if (f) fputs("precious", f), fclose(f);
  char link[512];
  snprintf(link, sizeof link, "%s/b", dir);
  t_true("plant a symlink as subfolder b", symlink(outside, link) == 0);
  char p[512];
  t_true("a write through a symlinked subfolder is refused",
         sessile_run_file(r, "b/victim.json", p, sizeof p) == SESSILE_ERR_IO);
  snprintf(link, sizeof link, "%s/final.json", dir);
  t_true("plant a symlink at a final name", symlink(path, link) == 0);
  write_small(r, "final.json", "new");
  char *v = slurp(path);
  t_true("the symlink's target is untouched", v && !strcmp(v, "precious"));
  free(v);
  struct stat st;
  t_true("the final name is now a regular file", lstat(link, &st) == 0 && S_ISREG(st.st_mode));
  snprintf(link, sizeof link, "%s/planted.csv", dir);
  t_true("plant a symlink at a log's name", symlink(path, link) == 0);
  t_true("a log through a symlink is refused",
         sessile_run_log(r, "planted.csv", "z\n", 2) == SESSILE_ERR_IO && strstr(sessile_error_message(), "symlink"));
  v = slurp(path);
  t_true("... and its target is untouched", v && !strcmp(v, "precious"));
  free(v);
  snprintf(link, sizeof link, "%s/fifo.csv", dir);
  t_true("plant a FIFO at a log's name", mkfifo(link, 0600) == 0);
  t_true("a log on a FIFO is refused at once (no hang)",
         sessile_run_log(r, "fifo.csv", "z\n", 2) == SESSILE_ERR_IO && strstr(sessile_error_message(), "regular"));
  t_ok("close", sessile_run_close(r, SESSILE_OK));

  /* A damaged checkpoint is reported, not trusted. */
  t_ok("open to checkpoint", open_run(SESSILE_RUN_REPLACE, &r));
  t_ok("set the config", sessile_run_set_config(r, cJSON_CreateString("cfg")));
  t_ok("a checkpoint", sessile_run_checkpoint(r, 3, 1, &sec));
  t_ok("close", sessile_run_close(r, SESSILE_OK));
  snprintf(path, sizeof path, "%s/checkpoint.bin", dir);
  int fd = open(path, O_WRONLY);
  t_true("flip a byte of the checkpoint", fd >= 0 && pwrite(fd, "X", 1, 40) == 1);
  if (fd >= 0) close(fd);
  t_true("a damaged checkpoint is reported", open_run(SESSILE_RUN_RESUME, &r) == SESSILE_ERR_IO &&
                                                 strstr(sessile_error_message(), "damaged"));

  /* A folder that is not empty and holds no run. */
  char other[200];
  snprintf(other, sizeof other, "%.180s/c", outside);
  mkdir(other, 0700);
  snprintf(dir, sizeof dir, "%.180s", outside);
  t_true("a non-run folder is refused even with --force", open_run(SESSILE_RUN_REPLACE, &r) == SESSILE_ERR_USAGE);
  struct stat lk;
  snprintf(path, sizeof path, "%s/.sessile.lock", dir);
  t_true("... and nothing is written into it (no lock file)", lstat(path, &lk) != 0);
  t_true("nothing to resume in a non-run folder", open_run(SESSILE_RUN_RESUME, &r) == SESSILE_ERR_USAGE);

  /* What a run killed before its manifest leaves (lock owner, empty
   * records, a temporary) is not a foreign folder: a new run takes it,
   * with nothing to resume; non-empty records would be someone's data. */
  snprintf(dir, sizeof dir, "%.180s/killed", outside);
  mkdir(dir, 0700);
  const char *left[] = {".sessile.lock", "records.jsonl", ".manifest.json.sessile-tmp.1234"};
  for (int i = 0; i < 3; i++) {
    snprintf(path, sizeof path, "%s/%s", dir, left[i]);
    int lf = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (lf >= 0 && i == 0) t_true("write a dead owner", write(lf, "pid 1\n", 6) == 6);
    if (lf >= 0) close(lf);
  }
  t_true("a killed start's folder has nothing to resume", open_run(SESSILE_RUN_RESUME, &r) == SESSILE_ERR_USAGE &&
                                                             strstr(sessile_error_message(), "start it again"));
  t_ok("a new run takes a killed start's folder", open_run(SESSILE_RUN_NEW, &r));
  t_ok("close", sessile_run_close(r, SESSILE_OK));
  t_true("... and its temporary is swept", !exists(".manifest.json.sessile-tmp.1234"));
  t_true("... and it holds a manifest now", exists("manifest.json"));
  snprintf(dir, sizeof dir, "%.180s/killed2", outside);
  mkdir(dir, 0700);
  snprintf(path, sizeof path, "%s/records.jsonl", dir);
  FILE *rf = fopen(path, "w");
  if (rf) fputs("{\"iteration\":1}\n", rf);
  if (rf) fclose(rf);
  t_true("records with data are not a leftover: refused", open_run(SESSILE_RUN_NEW, &r) == SESSILE_ERR_USAGE);
  cJSON_Delete(rec);
  char cmd[300];
  outside[strlen(outside) - strlen("-outside")] = 0;
  snprintf(cmd, sizeof cmd, "rm -rf '%s' '%s-outside'", outside, outside);
  if (system(cmd) != 0) printf("note: could not remove the test folders\n");
  return t_finish(NULL);
}
