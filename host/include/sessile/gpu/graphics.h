/* sessile — offscreen graphics on the compute context (host/gpu/graphics*.c),
 * public so that host/render draws through it; the renderer is its one user.  A target is a w x h RGBA8 colour image (UNORM: shader values
 * are written as they are, no sRGB encoding), a depth buffer, optionally
 * multisampled with a resolve, one render pass and framebuffer, and a
 * host-visible readback buffer.  Pipelines are made for a target once and
 * reused for every frame; buffers hold vertices or 32-bit indices.
 *
 * Vulkan 1.0 render passes (no dynamic rendering), so any device with a
 * graphics queue works.  Everything runs on the context's graphics queue
 * with its own command pool; each frame is submitted and waited for. */
#ifndef SESSILE_GPU_GRAPHICS_H
#define SESSILE_GPU_GRAPHICS_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/gpu/gpu.h"

typedef struct sessile_gfx_target sessile_gfx_target;
typedef struct sessile_gfx_pipeline sessile_gfx_pipeline;
typedef struct sessile_gfx_buffer sessile_gfx_buffer;

/* Sample counts (bit n = 2^n samples, as VkSampleCountFlags) usable for
 * both an RGBA8 colour and the depth attachment; 0 when the context has no
 * graphics queue. */
uint32_t sessile_gfx_sample_counts(const sessile_gpu *g);
/* The largest framebuffer side the device allows. */
uint32_t sessile_gfx_max_side(const sessile_gpu *g);

/* samples: 1, 2, 4, 8 ... among sessile_gfx_sample_counts (else USAGE). */
sessile_status sessile_gfx_target_create(sessile_gpu *g, uint32_t width, uint32_t height,
                                         uint32_t samples, sessile_gfx_target **out);
void sessile_gfx_target_destroy(sessile_gfx_target *t);
/* Device bytes a target of this size would take (colour, depth, resolve, readback). */
uint64_t sessile_gfx_target_bytes(uint32_t width, uint32_t height, uint32_t samples);

typedef enum sessile_gfx_topology {
  SESSILE_GFX_TRIANGLES = 0,
  SESSILE_GFX_LINES = 1
} sessile_gfx_topology;

typedef enum sessile_gfx_format {
  SESSILE_GFX_FLOAT3 = 0,   /* vec3 from 3 floats */
  SESSILE_GFX_UNORM8X4 = 1, /* vec4 from 4 bytes / 255 */
  SESSILE_GFX_FLOAT4 = 2    /* vec4 from 4 floats */
} sessile_gfx_format;

typedef struct sessile_gfx_attr {
  sessile_gfx_format format;
  uint32_t offset;  /* bytes into the vertex (or the instance) */
  uint32_t binding; /* 0: per vertex; 1: per instance (the draw's instance buffer) */
} sessile_gfx_attr;

typedef struct sessile_gfx_pipeline_desc {
  const char *vert, *frag; /* embedded SPIR-V names ("render/mesh.vert") */
  uint32_t stride;         /* bytes per vertex (binding 0) */
  uint32_t instance_stride; /* bytes per instance (binding 1), 0: no per-instance attributes */
  uint32_t nattr;          /* locations 0..nattr-1 (at most 8) */
  sessile_gfx_attr attr[8];
  sessile_gfx_topology topology;
  uint32_t push_bytes;     /* push constants of both stages, at most 128 */
} sessile_gfx_pipeline_desc;

/* Depth test LESS with writes, no culling, no blending. */
sessile_status sessile_gfx_pipeline_create(sessile_gfx_target *t, const sessile_gfx_pipeline_desc *d,
                                           sessile_gfx_pipeline **out);
void sessile_gfx_pipeline_destroy(sessile_gfx_pipeline *p);

typedef enum sessile_gfx_usage { SESSILE_GFX_VERTEX = 0, SESSILE_GFX_INDEX = 1 } sessile_gfx_usage;
/* A device buffer of `bytes` filled from data (staged on discrete devices). */
sessile_status sessile_gfx_buffer_create(sessile_gpu *g, sessile_gfx_usage usage, const void *data,
                                         size_t bytes, sessile_gfx_buffer **out);
void sessile_gfx_buffer_destroy(sessile_gfx_buffer *b);

/* One draw: `count` indices of `indices` (32-bit) from first_index or, when
 * indices is NULL, `count` vertices of `vertices`.  With `instances` (the
 * pipeline's binding 1), ninstances instances from first_instance; without,
 * one. */
typedef struct sessile_gfx_draw {
  const sessile_gfx_pipeline *pipeline;
  const sessile_gfx_buffer *vertices, *indices;
  uint32_t count;
  const void *push; /* the pipeline's push_bytes */
  const sessile_gfx_buffer *instances;
  uint32_t first_index, first_instance, ninstances;
} sessile_gfx_draw;

/* Clears to `clear` (RGBA in [0, 1]) and depth 1, records the draws in
 * order, resolves, and copies the w x h RGBA8 pixels (row 0 at the top) to
 * rgba.  Seconds spent drawing (submit to fence) and reading back (copy,
 * wait, memcpy) go to the optional t_draw, t_read. */
sessile_status sessile_gfx_render(sessile_gfx_target *t, const float clear[4],
                                  const sessile_gfx_draw *draws, uint32_t ndraws, unsigned char *rgba,
                                  double *t_draw, double *t_read);

#endif
