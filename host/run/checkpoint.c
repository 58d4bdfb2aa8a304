/* checkpoint.bin: the state a run resumes from, written atomically.
 *
 * Layout (little-endian): the magic line "SESSILE-CHECKPOINT 1\n", u32
 * section count, then per section u32 name length, the name, u64 size, u32
 * CRC-32 of the data, the data; last a u32 CRC-32 of everything before it.
 * The run's own section "run" (JSON: iteration, records length) comes first.
 * A checkpoint is read on the machine that wrote it: the sections hold the
 * generator's arrays in host byte order. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include "run_internal.h"
#include "sessile/io/io.h"

static const char MAGIC[] = "SESSILE-CHECKPOINT 1\n";
#define MAGIC_LEN (sizeof MAGIC - 1)
#define CKPT_MAX_BYTES ((size_t)1 << 36)

static uint32_t crc(const void *p, size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  const Bytef *b = p;
  while (n) { /* zlib takes uInt lengths */
    uInt k = n > 1u << 30 ? 1u << 30 : (uInt)n;
    c = crc32(c, b, k);
    b += k, n -= k;
  }
  return (uint32_t)c;
}

static void put32(uint8_t *p, uint32_t v) {
  for (int i = 0; i < 4; i++) p[i] = (uint8_t)(v >> (8 * i));
}
static void put64(uint8_t *p, uint64_t v) {
  for (int i = 0; i < 8; i++) p[i] = (uint8_t)(v >> (8 * i));
}
static uint32_t get32(const uint8_t *p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; i++) v |= (uint32_t)p[i] << (8 * i);
  return v;
}
static uint64_t get64(const uint8_t *p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; i++) v |= (uint64_t)p[i] << (8 * i);
  return v;
}

sessile_status sessile_run_checkpoint(sessile_run *r, int iteration, int nsections,
                                      const sessile_ckpt_section *sections) {
  cJSON *own = cJSON_CreateObject();
  SESSILE_CHECK(own, SESSILE_ERR_NO_MEMORY, "out of host memory for a checkpoint");
  cJSON_AddNumberToObject(own, "iteration", iteration);
  cJSON_AddNumberToObject(own, "records_bytes", (double)r->records_bytes);
  run_log_len logs[RUN_MAX_LOGS];
  int nlogs;
  run_logs_to_keep(r, logs, &nlogs);
  /* who the state belongs to, and which files it goes with (a resume
   * refuses another run's checkpoint and removes files written after it) */
  char idt[16];
  run_config_identity(r->config, idt);
  cJSON_AddStringToObject(own, "config", idt);
  cJSON *files = cJSON_Duplicate(cJSON_GetObjectItemCaseSensitive(r->manifest, "files"), 1);
  if (files) cJSON_AddItemToObject(own, "files", files);
  cJSON *lj = nlogs ? cJSON_AddObjectToObject(own, "logs") : NULL;
  for (int i = 0; lj && i < nlogs; i++) cJSON_AddNumberToObject(lj, logs[i].rel, (double)logs[i].bytes);
  if (!files || (nlogs && (!lj || cJSON_GetArraySize(lj) != nlogs))) {
    cJSON_Delete(own);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a checkpoint");
  }
  char *own_text = cJSON_PrintUnformatted(own);
  cJSON_Delete(own);
  SESSILE_CHECK(own_text, SESSILE_ERR_NO_MEMORY, "out of host memory for a checkpoint");
  sessile_ckpt_section all[65];
  SESSILE_CHECK(nsections >= 0 && nsections < 64, SESSILE_ERR_INTERNAL, "checkpoint: %d sections", nsections);
  all[0] = (sessile_ckpt_section){"run", own_text, strlen(own_text)};
  for (int i = 0; i < nsections; i++) all[i + 1] = sections[i];
  int n = nsections + 1;

  /* the records and logs up to here are part of the state: durable before
   * the checkpoint that counts their lengths, so a crash never leaves a
   * checkpoint longer than its files */
  if (r->recfd >= 0) fdatasync(r->recfd);
  run_logs_sync(r);
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", r->dir, RUN_CHECKPOINT);
  sessile_atomic_file af;
  sessile_status s = sessile_atomic_open(path, &af);
  if (s != SESSILE_OK) {
    free(own_text);
    return s;
  }
  uLong total = crc32(0L, Z_NULL, 0);
  uint8_t hdr[4];
  put32(hdr, (uint32_t)n);
  int ok = fwrite(MAGIC, 1, MAGIC_LEN, af.f) == MAGIC_LEN && fwrite(hdr, 1, 4, af.f) == 4;
  total = crc32(total, (const Bytef *)MAGIC, (uInt)MAGIC_LEN);
  total = crc32(total, hdr, 4);
  for (int i = 0; ok && i < n; i++) {
    uint32_t nl = (uint32_t)strlen(all[i].name);
    uint8_t h[4 + 8 + 4];
    put32(h, nl);
    ok = fwrite(h, 1, 4, af.f) == 4 && fwrite(all[i].name, 1, nl, af.f) == nl;
    total = crc32(total, h, 4);
    total = crc32(total, (const Bytef *)all[i].name, nl);
    put64(h, all[i].bytes);
    put32(h + 8, crc(all[i].data, all[i].bytes));
    ok = ok && fwrite(h, 1, 12, af.f) == 12 &&
         (all[i].bytes == 0 || fwrite(all[i].data, 1, all[i].bytes, af.f) == all[i].bytes);
    total = crc32(total, h, 12);
    const Bytef *b = all[i].data;
    for (size_t left = all[i].bytes; left;) {
      uInt k = left > 1u << 30 ? 1u << 30 : (uInt)left;
      total = crc32(total, b, k);
      b += k, left -= k;
    }
  }
  put32(hdr, (uint32_t)total);
  ok = ok && fwrite(hdr, 1, 4, af.f) == 4;
  free(own_text);
  if (!ok) {
    int e = errno;
    sessile_atomic_abort(&af);
    return sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': %s", path, strerror(e));
  }
  SESSILE_CALL(sessile_atomic_commit(&af));
  cJSON *ck = cJSON_CreateObject();
  SESSILE_CHECK(ck, SESSILE_ERR_NO_MEMORY, "out of host memory for the manifest");
  cJSON_AddStringToObject(ck, "file", RUN_CHECKPOINT);
  cJSON_AddNumberToObject(ck, "iteration", iteration);
  if (cJSON_GetObjectItemCaseSensitive(r->manifest, "checkpoint"))
    cJSON_ReplaceItemInObjectCaseSensitive(r->manifest, "checkpoint", ck);
  else cJSON_AddItemToObject(r->manifest, "checkpoint", ck);
  return sessile_run_write_manifest(r);
}

void run_ckpt_free(sessile_ckpt *c) {
  if (!c) return;
  cJSON_Delete(c->files);
  for (int i = 0; i < c->n; i++) free(c->e[i].name);
  free(c->e);
  free(c->blob);
  free(c);
}

static sessile_status damaged(const sessile_run *r, const char *why) {
  return sessile_error_set(SESSILE_ERR_IO,
                           "'%s/%s' is damaged (%s); move it away to restart the run from its "
                           "beginning with --resume", r->dir, RUN_CHECKPOINT, why);
}

/* Parses the blob into c (bounds and CRCs checked). */
static sessile_status parse(const sessile_run *r, sessile_ckpt *c, size_t len) {
  const uint8_t *b = c->blob;
  if (len < MAGIC_LEN + 8 || memcmp(b, MAGIC, MAGIC_LEN)) return damaged(r, "not a sessile checkpoint");
  if (get32(b + len - 4) != crc(b, len - 4)) return damaged(r, "checksum mismatch");
  size_t at = MAGIC_LEN;
  uint32_t n = get32(b + at);
  at += 4;
  if (n == 0 || n > 64) return damaged(r, "section count");
  c->e = calloc(n, sizeof *c->e);
  SESSILE_CHECK(c->e, SESSILE_ERR_NO_MEMORY, "out of host memory reading the checkpoint");
  for (uint32_t i = 0; i < n; i++) {
    if (len - 4 - at < 4) return damaged(r, "truncated");
    uint32_t nl = get32(b + at);
    at += 4;
    if (nl == 0 || nl > 256 || len - 4 - at < (size_t)nl + 12) return damaged(r, "truncated");
    c->e[i].name = malloc(nl + 1);
    SESSILE_CHECK(c->e[i].name, SESSILE_ERR_NO_MEMORY, "out of host memory reading the checkpoint");
    memcpy(c->e[i].name, b + at, nl);
    c->e[i].name[nl] = 0;
    c->n = (int)i + 1;
    at += nl;
    uint64_t sz = get64(b + at);
    uint32_t sc = get32(b + at + 8);
    at += 12;
    if (sz > len - 4 - at) return damaged(r, "truncated");
    c->e[i].data = b + at;
    c->e[i].bytes = (size_t)sz;
    if (crc(b + at, (size_t)sz) != sc) return damaged(r, "section checksum mismatch");
    at += (size_t)sz;
  }
  if (at != len - 4) return damaged(r, "trailing bytes");
  size_t ol = 0;
  const char *own = sessile_ckpt_get(c, "run", &ol);
  if (!own) return damaged(r, "no run section");
  cJSON *j = cJSON_ParseWithLength(own, ol);
  const cJSON *it = cJSON_GetObjectItemCaseSensitive(j, "iteration");
  const cJSON *rb = cJSON_GetObjectItemCaseSensitive(j, "records_bytes");
  int good = cJSON_IsNumber(it) && cJSON_IsNumber(rb) && it->valuedouble >= 0 && rb->valuedouble >= 0;
  if (good) {
    c->iteration = (int)it->valuedouble;
    c->records_bytes = (uint64_t)rb->valuedouble;
  }
  /* the logs' lengths (sessile_run_log; absent in a checkpoint without logs) */
  const cJSON *lj = cJSON_GetObjectItemCaseSensitive(j, "logs"), *l;
  if (good && lj) good = cJSON_IsObject(lj);
  if (good) cJSON_ArrayForEach(l, lj) {
    if (!(cJSON_IsNumber(l) && l->valuedouble >= 0 && l->string && strlen(l->string) < RUN_LOG_NAME &&
          c->nlogs < RUN_MAX_LOGS)) {
      good = 0;
      break;
    }
    snprintf(c->logs[c->nlogs].rel, RUN_LOG_NAME, "%s", l->string);
    c->logs[c->nlogs++].bytes = (uint64_t)l->valuedouble;
  }
  /* the run's identity and file list (absent in checkpoints of older versions) */
  const cJSON *id = cJSON_GetObjectItemCaseSensitive(j, "config");
  if (good && id) good = cJSON_IsString(id) && strlen(id->valuestring) < sizeof c->config_id;
  if (good && id) snprintf(c->config_id, sizeof c->config_id, "%s", id->valuestring);
  cJSON *fl = cJSON_DetachItemFromObjectCaseSensitive(j, "files");
  if (good && fl) good = cJSON_IsArray(fl);
  if (good) c->files = fl;
  else cJSON_Delete(fl);
  cJSON_Delete(j);
  return good ? SESSILE_OK : damaged(r, "run section");
}

sessile_status run_ckpt_read(sessile_run *r) {
  char *text = NULL;
  size_t len = 0;
  SESSILE_CALL(run_read_file(r->dfd, RUN_CHECKPOINT, CKPT_MAX_BYTES, &text, &len));
  r->records_bytes = 0;
  if (!text) return SESSILE_OK;
  sessile_ckpt *c = calloc(1, sizeof *c);
  if (!c) {
    free(text);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory reading the checkpoint");
  }
  c->blob = (uint8_t *)text;
  sessile_status s = parse(r, c, len);
  if (s != SESSILE_OK) {
    run_ckpt_free(c);
    return s;
  }
  r->ckpt = c;
  r->records_bytes = c->records_bytes;
  return SESSILE_OK;
}

void run_config_identity(const cJSON *config, char out[16]) {
  snprintf(out, 16, "none");
  cJSON *c = config ? cJSON_Duplicate(config, 1) : NULL;
  if (!c) return;
  cJSON_DeleteItemFromObjectCaseSensitive(c, "iterations"); /* a resume may raise it */
  /* printed, parsed and printed again: a stored config holds numbers as
   * 17-digit raw text, which cJSON prints back in its shortest form */
  char *text = cJSON_PrintUnformatted(c);
  cJSON_Delete(c);
  c = text ? cJSON_Parse(text) : NULL;
  free(text);
  text = c ? cJSON_PrintUnformatted(c) : NULL;
  cJSON_Delete(c);
  if (!text) return;
  snprintf(out, 16, "%08x", (unsigned)crc(text, strlen(text)));
  free(text);
}

sessile_status run_ckpt_check_identity(const sessile_run *r) {
  /* an older checkpoint, or one written before the run had a configuration */
  if (!r->ckpt || !r->ckpt->config_id[0] || !strcmp(r->ckpt->config_id, "none")) return SESSILE_OK;
  char idt[16];
  run_config_identity(r->config, idt);
  SESSILE_CHECK(!strcmp(idt, r->ckpt->config_id), SESSILE_ERR_USAGE,
                "'%s/%s' was written by another model or configuration (not this run's, whose seed and "
                "parameters differ): move it away to restart the run from its beginning",
                r->dir, RUN_CHECKPOINT);
  return SESSILE_OK;
}

sessile_status sessile_ckpt_take(const sessile_ckpt *c, const char *name, void *dst, size_t bytes) {
  size_t n = 0;
  const void *p = sessile_ckpt_get(c, name, &n);
  SESSILE_CHECK(p, SESSILE_ERR_IO, "the checkpoint has no '%s' section", name);
  SESSILE_CHECK(n == bytes, SESSILE_ERR_IO, "the checkpoint's '%s' section holds %zu bytes, not the %zu this run needs",
                name, n, bytes);
  if (bytes) memcpy(dst, p, bytes);
  return SESSILE_OK;
}

const sessile_ckpt *sessile_run_checkpoint_loaded(const sessile_run *r) { return r->ckpt; }

int sessile_ckpt_iteration(const sessile_ckpt *c) { return c ? c->iteration : 0; }

const void *sessile_ckpt_get(const sessile_ckpt *c, const char *name, size_t *bytes) {
  for (int i = 0; c && i < c->n; i++)
    if (!strcmp(c->e[i].name, name)) {
      if (bytes) *bytes = c->e[i].bytes;
      return c->e[i].data;
    }
  if (bytes) *bytes = 0;
  return NULL;
}
