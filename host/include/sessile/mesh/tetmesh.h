/* sessile — a general tetrahedral mesh of the water: the structured box
 * (immersed domain) converted, or TetGen's mesh of the box minus the sponge
 * (conforming domain).  The finite-element layer (fem) assembles on this.
 *
 * Node and face tags are the box's SESSILE_TAG_* bits plus
 * SESSILE_TAG_SPONGE for the sponge surface of a conforming mesh.
 * Tetrahedra are positively oriented: det[x1-x0, x2-x0, x3-x0] > 0.
 * Ownership: the struct owns its arrays; sessile_tetmesh_free releases them
 * (a zeroed struct is valid and empty). */
#ifndef SESSILE_TETMESH_H
#define SESSILE_TETMESH_H

#include <stdint.h>
#include "sessile/mesh/box.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { SESSILE_TAG_SPONGE = 32u };

typedef struct sessile_tetmesh {
  uint32_t nnodes, ntets, nbfaces;
  double *xyz;          /* 3 nnodes, cm */
  uint32_t *tet;        /* 4 ntets */
  uint32_t *node_tags;  /* nnodes: OR of the tags of the boundary faces touching the node */
  uint32_t *bface;      /* 3 nbfaces: boundary triangles, counter-clockwise seen from outside the water */
  uint32_t *bface_tag;  /* nbfaces: exactly one SESSILE_TAG_* bit each */
} sessile_tetmesh;

void sessile_tetmesh_free(sessile_tetmesh *m);

/* The structured box as a general mesh: node i of the box is node i here,
 * 6 Kuhn tets per cube (sessile_box_tet order), boundary faces tagged by the
 * box side they lie on. */
sessile_status sessile_tetmesh_from_box(const sessile_box *box, sessile_tetmesh *out);

/* Signed volume of tet t (cm^3). */
double sessile_tetmesh_tet_volume(const sessile_tetmesh *m, uint32_t t);

#ifdef __cplusplus
}
#endif
#endif
