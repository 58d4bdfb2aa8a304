/* Access to a vector's device buffer for other layers' kernels (growth reads
 * the nutrient field in place): n reals of the context precision, padded
 * with zeros to a multiple of 4. */
#include "la_internal.h"

sessile_buffer *sessile_vec_buffer(const sessile_vec *v) { return v->buf; }
