/* The per-vertex groom of a fur (Lengyel et al. 2001 §3; pelt/groom.h):
 * stored as the renderer uploads it, with a version and the range of
 * vertices changed since the renderer last looked. No GL here. */
#ifndef PELT_CORE_FUR_GROOM_H
#define PELT_CORE_FUR_GROOM_H

#include "pelt/groom.h"

/* One vertex, 20 bytes, uploaded as is (PELT_ATTR_GROOM, PELT_ATTR_HAIR_COLOR). */
typedef struct pelt__groom_vertex {
    float lean[2];    /* tangential tip offset per unit length, frame (u, v) */
    float length;     /* multiple of the fur length */
    float density;    /* 0..1 */
    uint8_t color[4]; /* hair colour and its weight, 0..255 */
} pelt__groom_vertex;

typedef struct pelt__groom {
    pelt_allocator alloc;
    size_t count;
    pelt__groom_vertex *v;
    uint32_t *stamp;     /* per vertex: the stroke that last visited it */
    uint32_t stroke;     /* the current stroke's stamp */
    unsigned version;    /* bumped on every change */
    size_t dirty_lo, dirty_hi; /* vertices [lo, hi) changed since the last take */
} pelt__groom;

pelt_status pelt__groom_init(pelt__groom *g, size_t count, const pelt_allocator *alloc,
                             pelt_error *err);
void pelt__groom_free(pelt__groom *g);

/* Vertex i as the public value, and back (clamped; false when not finite). */
pelt_groom_value pelt__groom_get(const pelt__groom *g, size_t i);
bool pelt__groom_pack(const pelt_groom_value *value, pelt__groom_vertex *out);

/* Records that vertices [lo, hi) changed. */
void pelt__groom_changed(pelt__groom *g, size_t lo, size_t hi);

/* Takes the changed range; false when nothing changed. */
bool pelt__groom_take_dirty(pelt__groom *g, size_t range[2]);

#endif
