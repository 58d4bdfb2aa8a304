/* sessile — the generators' random numbers: one splitmix64 stream per use,
 * seeded from the user's --seed, so the same seed gives the same bytes.  The
 * state is one uint64_t: checkpoint it to resume the same sequence. */
#ifndef SESSILE_RNG_H
#define SESSILE_RNG_H
#include <math.h>
#include <stdint.h>

/* splitmix64's step (the golden-ratio increment) and its output mix: the
 * n-th output of a stream started at s is sessile_rng_mix(s + n GAMMA), so
 * a parallel fill can compute any output directly. */
#define SESSILE_RNG_GAMMA 0x9E3779B97F4A7C15ull
static inline uint64_t sessile_rng_mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
static inline uint64_t sessile_rng_next(uint64_t *state) { return sessile_rng_mix(*state += SESSILE_RNG_GAMMA); }
/* Uniform in [0, 1) with 53 random bits. */
static inline double sessile_rng_uniform(uint64_t *state) {
  return (double)(sessile_rng_next(state) >> 11) * (1.0 / 9007199254740992.0);
}
/* Uniform in [lo, hi). */
static inline double sessile_rng_range(uint64_t *state, double lo, double hi) {
  return lo + (hi - lo) * sessile_rng_uniform(state);
}
/* Standard normal (Box-Muller, both draws consumed: no hidden state). */
static inline double sessile_rng_normal(uint64_t *state) {
  double u1 = sessile_rng_uniform(state), u2 = sessile_rng_uniform(state);
  return sqrt(-2.0 * log(1.0 - u1)) * cos(6.283185307179586 * u2);
}
/* A stream for a named purpose from one seed: independent sequences per use. */
static inline uint64_t sessile_rng_stream(uint64_t seed, uint64_t purpose) {
  uint64_t s = seed ^ (purpose * 0xD1B54A32D192ED03ull);
  return sessile_rng_next(&s);
}
#endif
