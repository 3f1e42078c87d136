/* pelt — grooming: local control of hair colour, length, density and
 * direction (Lengyel et al. 2001 §3), brushes for tools and scripts, and a
 * groom file that keeps an artist's edits. docs/grooming.md has pictures.
 *
 * Lengyel et al. store a colour and a vector c_v per mesh vertex: its part
 * along the normal is the hair length, its tangential part combs the hair.
 * pelt keeps, per vertex of the fur's mesh, a length scale (c_v's normal
 * part over the fur length), a lean (c_v's tangential part over the
 * length, in the vertex's tangent frame), a density and a hair colour.
 * Everything is interpolated across triangles, so neighbouring shells stay
 * joined wherever the length changes. */
#ifndef PELT_GROOM_H
#define PELT_GROOM_H

#include "pelt/base.h"
#include "pelt/fur.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What one vertex holds. */
typedef struct pelt_groom_value {
    float length;    /* multiple of the fur length, 0..PELT_GROOM_MAX_LENGTH,
                        default 1 (0: hair lies on the skin) */
    float density;   /* share of strands kept, 0..1, default 1 (0: bare skin) */
    float lean[2];   /* tangential tip offset per unit length along the
                        vertex's tangent frame (+u of the fur texture, and
                        normal x u): tan of the lean angle, |lean| at most
                        PELT_GROOM_MAX_LEAN; default 0 (the global comb.slant
                        still applies) */
    float color[4];  /* hair colour (sRGB) and its weight over the
                        fur's look.color in [0,1]; default weight 0 */
} pelt_groom_value;

#define PELT_GROOM_MAX_LENGTH 8.0f
#define PELT_GROOM_MAX_LEAN 1.7320508f /* tan 60 degrees, as comb.slant */

/* The untouched value: length 1, density 1, no lean, no colour. */
pelt_groom_value pelt_groom_value_default(void);

/* Vertices of the fur's mesh (the groom has one value each). */
size_t pelt_fur_vertex_count(const pelt_fur *fur);

/* One vertex's value; the default for an index out of range. */
pelt_groom_value pelt_fur_get_groom(const pelt_fur *fur, size_t vertex);

/* Sets vertices first .. first + count - 1. Values are clamped to their
 * ranges; a non-finite one is PELT_ERR_INVALID_ARGUMENT and nothing
 * changes. */
pelt_status pelt_fur_set_groom(pelt_fur *fur, size_t first, size_t count,
                               const pelt_groom_value *values, pelt_error *err);

/* Every vertex back to pelt_groom_value_default(). */
void pelt_fur_reset_groom(pelt_fur *fur);

/* ---- maps ----------------------------------------------------------------- */

/* Which field an image sets. */
typedef enum pelt_groom_field {
    PELT_GROOM_LENGTH = 0, /* grey (red channel) g -> length lo + g (hi - lo) */
    PELT_GROOM_DENSITY,    /* grey g -> density lo + g (hi - lo) */
    PELT_GROOM_FLOW,       /* flow map: lean = (2r - 1, 2g - 1) * hi, along
                              the vertex's tangent frame (u right, v up in
                              the image); lo unused */
    PELT_GROOM_COLOR       /* rgb -> hair colour, alpha -> its weight */
} pelt_groom_field;

/* Sets one field of every vertex from an RGBA8 image in the mesh's uv
 * space (for a patch atlas, the atlas's), bilinearly sampled at the
 * vertex's uv with wrapping; row 0 is the TOP of the image (v = 1), as a
 * picture is viewed and as wetness.mask_image reads. */
pelt_status pelt_fur_groom_from_image(pelt_fur *fur, pelt_groom_field field, const uint8_t *rgba,
                                      unsigned width, unsigned height, float lo, float hi,
                                      pelt_error *err);

/* The mesh file's vertex colours as hair colour (Lengyel's dog), weight 1.
 * PELT_ERR_INVALID_ARGUMENT when the mesh has none. */
pelt_status pelt_fur_groom_from_vertex_colors(pelt_fur *fur, pelt_error *err);

/* ---- brushes -------------------------------------------------------------- */

typedef enum pelt_brush_tool {
    PELT_BRUSH_COMB = 0, /* tips move by `delta` (its tangential part) */
    PELT_BRUSH_LENGTH,   /* length += amount */
    PELT_BRUSH_COLOR,    /* paint `color` over the hair colour */
    PELT_BRUSH_DENSITY   /* density moves towards `amount` */
} pelt_brush_tool;

/* A brush stroke: everything within `radius` of the centre, weighted by
 * the smooth falloff w = strength (1 - (d / radius)^2)^2. Positions, radius
 * and delta are mesh-local units (the mesh's own, before the model
 * matrix). */
typedef struct pelt_brush {
    pelt_brush_tool tool;
    float radius;     /* > 0 */
    float strength;   /* weight at the centre, (0, 1]; 0 = 1 */
    float delta[3];   /* COMB: tip displacement at the centre */
    float amount;     /* LENGTH: length added at the centre (negative
                         shortens); DENSITY: the density painted, 0..1 */
    float color[3];   /* COLOR: the colour painted, sRGB */
} pelt_brush;

/* Applies a stroke centred at `center`. The vertices are found through the
 * fur's triangle hierarchy (work grows with the vertices touched, not with
 * the mesh); nothing is allocated. *touched (may be NULL) gets the number
 * of vertices changed. */
pelt_status pelt_fur_brush(pelt_fur *fur, const float center[3], const pelt_brush *brush,
                           size_t *touched, pelt_error *err);

/* The stroke where a ray (mesh-local) first meets the mesh; false when it
 * misses or the brush is invalid. `hit` (may be NULL) gets the point. */
bool pelt_fur_brush_ray(pelt_fur *fur, const float origin[3], const float direction[3],
                        const pelt_brush *brush, float hit[3]);

/* ---- groom files ---------------------------------------------------------- */

/* Saves every vertex's groom as a binary PLY of the validated mesh (its
 * positions and triangles, the groom as vertex properties, the colour as
 * red/green/blue/alpha so mesh viewers show it). */
pelt_status pelt_fur_save_groom(const pelt_fur *fur, const char *path, pelt_error *err);

/* Loads a groom saved by pelt_fur_save_groom. Vertices are matched by
 * position (within 1e-5 of the mesh's diagonal), so the file survives a
 * different vertex order. A file that is not a pelt groom, is truncated,
 * holds a non-finite value, or does not cover every vertex of this mesh is
 * PELT_ERR_FORMAT with a message naming the file and what does not match;
 * the groom is then unchanged. */
pelt_status pelt_fur_load_groom(pelt_fur *fur, const char *path, pelt_error *err);

/* The same from memory; `name` starts every message. */
pelt_status pelt_fur_load_groom_memory(pelt_fur *fur, const void *data, size_t size,
                                       const char *name, pelt_error *err);

#ifdef __cplusplus
}
#endif
#endif
