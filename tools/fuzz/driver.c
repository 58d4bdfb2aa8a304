/* A plain main() for the fuzz target (fuzz_params.c) where libFuzzer is not
 * at hand (gcc, the CMake test fuzz_params_short): runs the target over
 * every file of the corpus folders, then over deterministic pseudo-random
 * mutations of them (a seeded xorshift64*: bit flips, byte sets, insertions
 * of bytes and of tokens -- parameter names, JSON punctuation, numbers --,
 * deletions, duplications, and splices between two corpus files) until a
 * count or a number of seconds is reached.  A crash or an abort() of the
 * target is the failure; with -w DIR the input about to run is written to
 * DIR/current first, so a crash leaves it behind.
 *
 *   fuzz_params_driver [-n COUNT] [-t SECONDS] [-s SEED] [-w DIR] [-v] CORPUS_DIR|FILE...
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include "sessile/run/param_table.h"
#include "sessile/growth/grow_params.h"
#include "sessile/sphere/sphere.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_INPUT = 8192 };

typedef struct buf {
  unsigned char *p;
  size_t n;
} buf;

static buf *corpus;
static size_t ncorpus, capcorpus;
static uint64_t rng_state;

static uint64_t rnd(void) { /* xorshift64* */
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return rng_state * 0x2545F4914F6CDD1Dull;
}
static size_t below(size_t n) { return n ? (size_t)(rnd() % n) : 0; }

static int add_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  unsigned char tmp[MAX_INPUT];
  size_t n = fread(tmp, 1, sizeof tmp, f);
  fclose(f);
  if (ncorpus == capcorpus) {
    capcorpus = capcorpus ? 2 * capcorpus : 64;
    corpus = realloc(corpus, capcorpus * sizeof *corpus);
    if (!corpus) return -1;
  }
  corpus[ncorpus].p = malloc(n ? n : 1);
  if (!corpus[ncorpus].p) return -1;
  memcpy(corpus[ncorpus].p, tmp, n);
  corpus[ncorpus++].n = n;
  return 0;
}

static int cmp_names(const void *a, const void *b) {
  return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* Every regular file of a folder, in name order (deterministic runs). */
static int add_path(const char *path) {
  struct stat st;
  if (stat(path, &st) != 0) return -1;
  if (!S_ISDIR(st.st_mode)) return add_file(path);
  DIR *d = opendir(path);
  if (!d) return -1;
  char **names = NULL;
  size_t n = 0, cap = 0;
  for (struct dirent *e; (e = readdir(d));) {
    if (e->d_name[0] == '.') continue;
    if (n == cap) {
      cap = cap ? 2 * cap : 64;
      char **nn = realloc(names, cap * sizeof *names);
      if (!nn) break;
      names = nn;
    }
    names[n++] = strdup(e->d_name);
  }
  closedir(d);
  qsort(names, n, sizeof *names, cmp_names);
  for (size_t i = 0; i < n; i++) {
    char full[4096];
    snprintf(full, sizeof full, "%s/%s", path, names[i]);
    if (stat(full, &st) == 0 && S_ISREG(st.st_mode)) add_file(full);
    free(names[i]);
  }
  free(names);
  return 0;
}

#ifndef FUZZ_WORDS
/* Tokens worth inserting: JSON structure, numbers at the edges of the
 * ranges and of double, spellings strtod takes that JSON does not. */
static const char *const tokens[] = {
    "{", "}", "[", "]", "\"", ":", ",", "=", "\n", " ", "true", "false", "null", "yes", "no",
    "0", "1", "-1", "2.5", "1e999", "-1e999", "1e-999", "nan", "NaN", "inf", "-inf", "Infinity",
    "0x1p3", "0x10", "1e308", "4.9e-324", "2147483648", "-2147483649", "4294967296",
    "18446744073709551616", "1e6", "1000001", "0.0", "-0", "+1", ".5", "5.", "1e", "\\u0000",
    "\\\"", "radiate", "halichondrid", "immersed", "conforming", "RADIATE", "{}", "[]",
    "{\"", "\":", "\": \"", "1.00000000000000000001", "99999999999999999999999", "\t", "\r",
};

#endif

static void insert(buf *b, size_t at, const unsigned char *s, size_t n) {
  if (b->n + n > MAX_INPUT) return;
  memmove(b->p + at + n, b->p + at, b->n - at);
  memcpy(b->p + at, s, n);
  b->n += n;
}

#ifdef FUZZ_WORDS
#include FUZZ_WORDS /* another target's tokens[] and param_name() */
#else
static const char *param_name(void) {
  const sessile_param_table *t = below(8) ? &sessile_grow_param_table : &sessile_sphere_param_table;
  return t->params[below((size_t)t->count)].name;
}
#endif

static void mutate(buf *b) {
  int rounds = 1 + (int)below(8);
  for (int r = 0; r < rounds; r++) {
    size_t at = below(b->n + 1);
    switch (below(10)) {
    case 0: /* flip a bit */
      if (b->n) b->p[below(b->n)] ^= (unsigned char)(1u << below(8));
      break;
    case 1: /* set a byte, printable most of the time */
      if (b->n) b->p[below(b->n)] = below(4) ? (unsigned char)(32 + below(95)) : (unsigned char)rnd();
      break;
    case 2: { /* insert a few bytes */
      unsigned char s[4];
      size_t n = 1 + below(4);
      for (size_t i = 0; i < n; i++) s[i] = below(4) ? (unsigned char)(32 + below(95)) : (unsigned char)rnd();
      insert(b, at, s, n);
      break;
    }
    case 3: { /* insert a token */
      const char *s = tokens[below(sizeof tokens / sizeof tokens[0])];
      insert(b, at, (const unsigned char *)s, strlen(s));
      break;
    }
    case 4: { /* insert a parameter name, quoted or as KEY= */
      char s[160];
      int k = (int)below(3);
      snprintf(s, sizeof s, k == 0 ? "\"%s\": " : k == 1 ? "%s=" : "%s", param_name());
      insert(b, at, (const unsigned char *)s, strlen(s));
      break;
    }
    case 5: case 6: { /* delete a range */
      if (!b->n) break;
      size_t from = below(b->n), len = 1 + below(b->n - from < 16 ? b->n - from : 16);
      memmove(b->p + from, b->p + from + len, b->n - from - len);
      b->n -= len;
      break;
    }
    case 7: { /* duplicate a chunk of itself */
      if (!b->n) break;
      size_t from = below(b->n), len = 1 + below(b->n - from);
      unsigned char tmp[MAX_INPUT];
      memcpy(tmp, b->p + from, len);
      insert(b, at, tmp, len);
      break;
    }
    case 8: { /* splice: the head of this one, the tail of another corpus file */
      const buf *o = &corpus[below(ncorpus)];
      size_t keep = below(b->n + 1), from = below(o->n + 1);
      if (keep + (o->n - from) > MAX_INPUT) break;
      memcpy(b->p + keep, o->p + from, o->n - from);
      b->n = keep + (o->n - from);
      break;
    }
    default: { /* replace a number-looking run with a token */
      if (!b->n) break;
      size_t i = below(b->n);
      while (i < b->n && !strchr("0123456789.eE+-", b->p[i])) i++;
      size_t j = i;
      while (j < b->n && strchr("0123456789.eE+-", b->p[j]) && b->p[j]) j++;
      if (j > i) {
        memmove(b->p + i, b->p + j, b->n - j);
        b->n -= j - i;
        const char *s = tokens[16 + below(30)];
        insert(b, i, (const unsigned char *)s, strlen(s));
      }
    }
    }
  }
}

static const char *work_dir;
static void run_one(const unsigned char *p, size_t n) {
  if (work_dir) {
    char path[4096];
    snprintf(path, sizeof path, "%s/current", work_dir);
    FILE *f = fopen(path, "wb");
    if (f) {
      fwrite(p, 1, n, f);
      fclose(f);
    }
  }
  /* an exact-size heap copy: ASan sees any read past the end */
  unsigned char *copy = malloc(n ? n : 1);
  if (!copy) return;
  memcpy(copy, p, n);
  LLVMFuzzerTestOneInput(copy, n);
  free(copy);
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv) {
  unsigned long long count = 20000, seed = 1;
  double seconds = 0;
  int verbose = 0, i = 1;
  for (; i < argc && argv[i][0] == '-'; i++) {
    if (!strcmp(argv[i], "-v")) verbose = 1;
    else if (i + 1 < argc && !strcmp(argv[i], "-n")) count = strtoull(argv[++i], NULL, 10);
    else if (i + 1 < argc && !strcmp(argv[i], "-t")) seconds = strtod(argv[++i], NULL);
    else if (i + 1 < argc && !strcmp(argv[i], "-s")) seed = strtoull(argv[++i], NULL, 10);
    else if (i + 1 < argc && !strcmp(argv[i], "-w")) work_dir = argv[++i];
    else {
      fprintf(stderr, "usage: %s [-n COUNT] [-t SECONDS] [-s SEED] [-w DIR] [-v] CORPUS_DIR|FILE...\n", argv[0]);
      return 2;
    }
  }
  for (; i < argc; i++)
    if (add_path(argv[i]) != 0) {
      fprintf(stderr, "fuzz_params_driver: cannot read '%s'\n", argv[i]);
      return 2;
    }
  if (!ncorpus) {
    fprintf(stderr, "fuzz_params_driver: no corpus files\n");
    return 2;
  }
  rng_state = seed * 0x9E3779B97F4A7C15ull + 1;
  double t0 = now();
  for (size_t k = 0; k < ncorpus; k++) run_one(corpus[k].p, corpus[k].n);
  buf b = {malloc(MAX_INPUT), 0};
  if (!b.p) return 1;
  unsigned long long done = 0;
  for (; done < count; done++) {
    if (seconds > 0 && (done & 63) == 0 && now() - t0 > seconds) break;
    /* from a corpus file most of the time, else keep mutating the last input */
    if (done == 0 || below(4)) {
      const buf *c = &corpus[below(ncorpus)];
      memcpy(b.p, c->p, c->n);
      b.n = c->n;
    }
    mutate(&b);
    if (verbose) fprintf(stderr, "input %llu: %zu bytes\n", done, b.n);
    run_one(b.p, b.n);
  }
  free(b.p);
  printf("fuzz_params_driver: %zu corpus files and %llu mutations (seed %llu) in %.1f s: no failure\n",
         ncorpus, done, seed, now() - t0);
  for (size_t k = 0; k < ncorpus; k++) free(corpus[k].p);
  free(corpus);
  return 0;
}
