/* sessile io — helpers shared by the writers (not public). */
#ifndef SESSILE_IO_INTERNAL_H
#define SESSILE_IO_INTERNAL_H
#include <stdint.h>
#include <string.h>
#include "sessile/io.h"

/* Little-endian stores, independent of the host's byte order. */
static inline uint8_t *io_put_u32(uint8_t *p, uint32_t v) {
  for (int b = 0; b < 4; b++) p[b] = (uint8_t)(v >> (8 * b));
  return p + 4;
}
static inline uint8_t *io_put_u64(uint8_t *p, uint64_t v) {
  for (int b = 0; b < 8; b++) p[b] = (uint8_t)(v >> (8 * b));
  return p + 8;
}
static inline uint8_t *io_put_f32(uint8_t *p, double v) {
  float f = (float)v;
  uint32_t u;
  memcpy(&u, &f, 4);
  return io_put_u32(p, u);
}
static inline uint8_t *io_put_f64(uint8_t *p, double v) {
  uint64_t u;
  memcpy(&u, &v, 8);
  return io_put_u64(p, u);
}

/* fwrite that records a SESSILE_ERR_IO naming the (final) file on failure. */
sessile_status io_write(sessile_atomic_file *af, const void *data, size_t bytes);
/* fprintf-like; same error reporting. */
sessile_status io_printf(sessile_atomic_file *af, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Writes s with XML's five special characters escaped (for attribute values). */
sessile_status io_xml_escaped(sessile_atomic_file *af, const char *s);

#endif
