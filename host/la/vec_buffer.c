/* The device buffer behind a vector, for kernels of higher layers (fem,
 * growth) that read or write fields in place. */
#include "la_internal.h"

sessile_buffer *sessile_vec_buffer(const sessile_vec *v) { return v->buf; }
