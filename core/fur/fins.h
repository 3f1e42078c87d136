/* Fins (Lengyel et al. 2001 §2.3): one quad per mesh edge, rising from the
 * skin along the displaced strands of its two end vertices, faded in as
 * the edge nears the silhouette. The edge list, the fin normal and the
 * fade that core/fur/fin_frame.c gives the fin pass. No GL here. */
#ifndef PELT_CORE_FUR_FINS_H
#define PELT_CORE_FUR_FINS_H

#include "core/base/vec.h"
#include "pelt/mesh.h"

/* One fin: the edge's end vertices (a < b) and where its interval of the
 * fin texture starts, in tiles, random per edge. */
typedef struct pelt__fin_edge {
    uint32_t a, b;
    float start;
} pelt__fin_edge;

/* Every edge of a triangle list once (the mesh's, or a level of detail's):
 * an edge two triangles share gets one fin, a border edge one too. *out
 * comes from `alloc`; free it with it. */
pelt_status pelt__fin_edges_build(const uint32_t *indices, size_t triangle_count, uint32_t seed,
                                  const pelt_allocator *alloc, pelt__fin_edge **out, size_t *count,
                                  pelt_error *err);

/* The fin's plane holds the edge and the mean of its end normals; its
 * normal is their cross product, unit (n of the first vertex when the
 * edge and normals are degenerate). */
pelt_vec3 pelt__fin_normal(pelt_vec3 pa, pelt_vec3 pb, pelt_vec3 na, pelt_vec3 nb);

/* Lengyel's fade: opacity times max(0, 2|p| - 1), p = fin normal . view
 * direction for the infinite viewer: 1 for a fin seen face on (its edge on
 * the silhouette), 0 once the fin turns 60 degrees away from that. */
float pelt__fin_fade(pelt_vec3 fin_normal, pelt_vec3 view_dir);

/* A fin stands for the hair in a slab `slab` fur tiles wide (the fin
 * texture's, pelt_fur_fins.density texels); fins closer together than that
 * (an edge `edge` tiles long) overlap, so each is made fainter by their
 * ratio: seen along the surface, the fins of a fine mesh then add up to
 * about the opacity of a coarser one's (a level of detail, or the same
 * creature modelled finer) instead of striping the silhouette. */
float pelt__fin_spacing_opacity(float edge, float slab);

/* The fin normal of every edge (pelt__fin_normal of its end points and
 * vertex normals), 3 floats per fin into `out`. */
void pelt__fin_normals(const pelt__fin_edge *edges, size_t count, const float *positions, const float *normals,
                       float *out);

#endif
