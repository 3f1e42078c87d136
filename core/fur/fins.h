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

/* The outline's hairs (gl/shaders/outline_hair.glsl, mirrored here and
 * parity-tested): a fin near the silhouette carries up to
 * PELT__OUTLINE_HAIRS_MAX of the hairs it stands for as geometry. */
#define PELT__OUTLINE_HAIRS_MAX 32

/* The seed of hair k on the fin between fin vertices a and b. */
uint32_t pelt__outline_seed(uint32_t a, uint32_t b, uint32_t k);

/* The fins whose fade is at least this carry hairs: those within about 40
 * degrees of the outline (Lengyel's fade 2|p| - 1, p the cosine). */
#define PELT__OUTLINE_LEAST_FADE 0.5f

/* The most hairs a frame draws (the table's room, 16 bytes each). */
#define PELT__OUTLINE_HAIR_BUDGET 65536

/* Where the outline's hairs of a frame are drawn from. */
typedef struct pelt__outline_frame {
    const float *vertices;  /* the fin vertex table: vertex v's root at
                               vertices[v * stride], its normal at
                               vertices[v * stride + normal] */
    size_t stride, normal;  /* floats */
    float eye[3];           /* the eye in mesh units */
    float tiles_per_unit;   /* fur tiles a mesh unit along an edge */
    float slab;             /* the fin texture's slab, fur tiles */
    float hairs;            /* hairs a fur tile of edge holds */
    float least;            /* the least fade that carries hairs */
    /* Where the view is known (view_proj not NULL), a fin whose hair is too
     * short or too long on screen for its hairs to carry any of the outline
     * (pelt__outline_share 0, as fin_outline_share in fin_table.glsl finds
     * it) lists none. */
    const float *view_proj, *model; /* column-major */
    float viewport[2];              /* pixels */
    size_t top;                     /* floats to the fin's top point from its root */
} pelt__outline_frame;

/* The fade of the fin from a to b (normals na, nb) seen from `eye`:
 * Lengyel's 2|p| - 1 with p the fin normal's cosine to the ray from the eye
 * to the edge's middle (a close view's outline is where that ray grazes,
 * not the view direction's), times pelt__fin_spacing_opacity. */
float pelt__outline_fade(pelt_vec3 a, pelt_vec3 b, pelt_vec3 na, pelt_vec3 nb, pelt_vec3 eye, float tiles_per_unit,
                         float slab);

/* The fin from a to b's hair length on screen, pixels, measured between
 * the middles of its roots and of its top points as fin_outline_share
 * (fin_table.glsl) measures it. */
float pelt__outline_hair_px(const pelt__outline_frame *f, const float *va, const float *vb);

/* The outline's hairs of a frame's fins (`fins`: `count` fins of 4 words,
 * the fin vertex table's indices a, b first, core/fur/fur_gpu.h): for every
 * fin whose pelt__outline_fade is at least f->least, its hairs
 * k < min(ceil(edge * hairs), MAX), edge its length in fur tiles, but
 * those whose threshold (pelt__outline_random's draw 3) is not below the
 * fade, which pelt__outline_alpha gives 0, those whose draw 5 is above
 * the groomed density at a (vertices[a * stride + normal + 3]), which
 * outline_vs.glsl leaves out, and those of a fin whose hair
 * on screen (pelt__outline_hair_px) is out of the outline's reach: written
 * as (a, b, k, fade bits) into `out`, at most `cap`. Returns how many. */
size_t pelt__outline_hairs(const uint32_t *fins, size_t count, const pelt__outline_frame *f, uint32_t *out,
                           size_t cap);

/* The hair's i-th draw, uniform in [0, 1): 0 its place along the edge,
 * 1 its length, 2 its lean, 3 the fade it shows from, 4 its shade, 5 its
 * id against the groomed density. */
float pelt__outline_random(uint32_t seed, uint32_t i);

/* How much of hair k its fin shows: its share of the fin's `count` hairs
 * and the fin's fade against the hair's threshold `show`; above 1 where
 * the fin stands for more hairs than PELT__OUTLINE_HAIRS_MAX (each drawn
 * one covers for count / MAX). */
float pelt__outline_alpha(float k, float count, float fade, float show);

/* The share of a fin's outline that its hairs carry (the rest the fin
 * texture's quads) by the hair's length on screen, pixels: 0 up to
 * PELT__OUTLINE_LOW_PX (every hair a fraction of a pixel), rising to 1 at
 * twice that, 1 up to PELT__OUTLINE_FULL_PX, 0 from PELT__OUTLINE_NONE_PX
 * (the texture resolves its hairs). outline_reach in GLSL. */
#define PELT__OUTLINE_LOW_PX 4.0f
#define PELT__OUTLINE_FULL_PX 16.0f
#define PELT__OUTLINE_NONE_PX 32.0f
float pelt__outline_reach(float hair_px);

/* The share of a fin's outline its hairs carry: pelt__outline_reach, none
 * where the fur holds water (the quads carry the tufts). */
float pelt__outline_share(float hair_px, float wetness);

/* The hair's lean along the edge at its tip, in its root widths. */
float pelt__outline_lean(float r);

/* The hair's point at h from its fin's strand point p at its root's place
 * on the edge, leaning along `along` (the edge's unit direction times the
 * hair's root width); its length share in out[3]. */
void pelt__outline_shape(pelt_vec3 root, pelt_vec3 p, pelt_vec3 along, float r_len, float r_lean, float h,
                         float out[4]);

#endif
