/* Seam-free droplets: a droplet wets the mask by distance on the surface,
 * not in texture space (Silva et al. §3.1, Alg. 1 applied per atlas patch;
 * docs/wetness.md). A drop on a patch border wets texels in
 * every patch within its radius, each storing the clump centre in its own
 * patch coordinates, so the clump renders as one. No GL here. */
#ifndef PELT_CORE_SURFACE_DROPLET_H
#define PELT_CORE_SURFACE_DROPLET_H

#include "core/mesh/raycast.h"
#include "core/wet/mask.h"

#include <stdint.h>

/* Built once per mesh: triangles around each welded position (vertices
 * split on patch borders or uv seams are joined again by exact position)
 * and the scratch one droplet needs, so pelt__droplet_surface never
 * allocates. The mesh is not copied: it must outlive the index and keep its
 * positions, uvs and indices. */
typedef struct pelt__surface_index {
    pelt_allocator alloc; /* the owner's; every array comes from it */
    const pelt_mesh *mesh;
    size_t triangle_count, welded_count;
    uint32_t *welded;     /* per vertex: welded position id */
    uint32_t *fan_start;  /* welded_count + 1 offsets into fan */
    uint32_t *fan;        /* triangles around each welded position */
    /* Scratch of one droplet (so an index is not shared by threads that
     * drop at the same time). Per triangle unless said otherwise. */
    uint32_t stamp;
    uint32_t *vert_stamp;  /* per welded position: fan scanned by `stamp` */
    uint32_t *tri_stamp;   /* reached by droplet `stamp` */
    float *tri_dist2;      /* its squared distance to the centre */
    uint32_t *queue;       /* breadth-first queue = the triangles in the ball */
    uint32_t *group_stamp; /* grouped by droplet `stamp` */
    uint32_t *group;       /* its piece of the ball connected in uv */
    uint32_t *stack;       /* flood fill of the pieces */
    uint32_t *group_ref;   /* per piece: its triangle nearest the centre */
    float *group_dist2;    /* per piece: that triangle's squared distance */
} pelt__surface_index;

/* Builds the index of mesh (positions, uvs and indices needed). Allocates
 * O(vertices + triangles) once; free with pelt__surface_index_destroy. */
pelt_status pelt__surface_index_create(const pelt_mesh *mesh, const pelt_allocator *a, pelt__surface_index **out,
                                       pelt_error *err);
void pelt__surface_index_destroy(pelt__surface_index *index);

/* A droplet at the surface point P = sum bary[k] * vertex k of `triangle`,
 * wetting every mask texel whose surface point X (barycentric blend of its
 * triangle's positions at the texel centre) has |X - P| <= radius_world.
 * Triangles are visited breadth-first from the hit triangle over shared
 * positions while their 3D distance to P is <= radius_world. The ball's
 * triangles fall into pieces connected in uv (across edges whose two ends
 * have the same uvs on both sides: a patch border or uv seam cuts them);
 * per piece the droplet is expressed through its triangle nearest P: the
 * clump centre c = that triangle's affine uv map at P projected on its
 * plane, r = radius_world * sqrt(uv area / world area) of that triangle;
 * then each texel gets Alg. 1 (docs/wetness.md) with (c, r, wetness),
 * wetness clamped to [-1, 1]. Texel centres on a shared uv edge belong to
 * one triangle (top-left rule on 1/256-texel fixed point, as
 * pelt_atlas_check_uvs counts them), so no texel is wetted twice. Grows
 * m->dirty and, for wetness > 0, m->wet like pelt__wetness_add_droplet.
 * Cost proportional to the triangles and texels touched. No allocation.
 * A bad triangle, non-finite bary / radius / wetness, a negative radius
 * or a mesh other than the index's give PELT_ERR_INVALID_ARGUMENT and
 * leave the mask unchanged. */
pelt_status pelt__droplet_surface(pelt__wetness *m, const pelt_mesh *mesh,
                                  pelt__surface_index *index, size_t triangle,
                                  const float bary[3], float radius_world, float wetness,
                                  pelt_error *err);

/* The one ray -> droplet path (a click, a rain drop): the closest hit of
 * the ray on bvh (built from mesh), then pelt__droplet_surface there with
 * radius_world and wetness. dir need not be unit length. Returns false on
 * a miss or when the droplet is refused (non-finite input, negative
 * radius); the mask is then unchanged. No allocation. */
bool pelt__droplet_ray(pelt__wetness *m, const pelt_mesh *mesh, pelt__surface_index *index,
                       const pelt__bvh *bvh, const float origin[3], const float dir[3],
                       float radius_world, float wetness);

#endif
