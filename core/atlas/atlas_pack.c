/* Packing: one scale for all patches, bisected until stb_rect_pack fits them with gutters (Lengyel §2.1). */
#include "core/atlas/atlas_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <math.h>
#include <stdlib.h>

#include <stb/stb_rect_pack.h>

/* Packs every patch box at s texels per world unit, padded by the gutter;
 * false when one does not fit. */
static bool try_pack(const pelt__atlas_builder *b, double s, unsigned size, stbrp_node *nodes,
                     stbrp_rect *rects)
{
    for (size_t p = 0; p < b->patch_count; p++) {
        const float *box = b->patch_box + 4 * p;
        double w = ceil((box[2] - box[0]) * s + 0.01) + 2 * PELT__ATLAS_GUTTER;
        double h = ceil((box[3] - box[1]) * s + 0.01) + 2 * PELT__ATLAS_GUTTER;
        if (w > size || h > size) return false;
        rects[p].id = (int)p;
        rects[p].w = (stbrp_coord)w;
        rects[p].h = (stbrp_coord)h;
        rects[p].was_packed = 0;
    }
    stbrp_context ctx;
    /* The atlas border counts as a neighbour: pack inside a 1-texel margin. */
    stbrp_init_target(&ctx, (int)size, (int)size, nodes, (int)size);
    return stbrp_pack_rects(&ctx, rects, (int)b->patch_count) == 1;
}

pelt_status pelt__atlas_pack(const pelt__atlas_builder *b, unsigned mask, float *uvs,
                             double *scale, double *used, pelt_error *err)
{
    /* One scale for all patches: area proportional to surface area. */
    double total = 0;
    for (size_t p = 0; p < b->patch_count; p++) {
        const float *box = b->patch_box + 4 * p;
        total += (double)(box[2] - box[0]) * (box[3] - box[1]);
    }
    stbrp_node *nodes = pelt__alloc_zero(&b->alloc, mask, sizeof(stbrp_node));
    stbrp_rect *rects = pelt__alloc_zero(&b->alloc, b->patch_count, sizeof(stbrp_rect));
    if (!nodes || !rects) {
        pelt__free(&b->alloc, nodes);
        pelt__free(&b->alloc, rects);
        return pelt__atlas_fail_oom(err, "packing");
    }
    double lo = 0.0, hi = total > 0 ? (double)mask / sqrt(total) : 1.0;
    if (!try_pack(b, 0.0, mask, nodes, rects)) {
        pelt__free(&b->alloc, nodes);
        pelt__free(&b->alloc, rects);
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_atlas_create: mask_size %u is too small for %zu patches with "
                          "their gutters; use a larger mask_size",
                          mask, b->patch_count);
    }
    for (int it = 0; it < 30; it++) {
        double mid = lo == 0.0 ? hi * 0.5 : sqrt(lo * hi);
        if (try_pack(b, mid, mask, nodes, rects)) lo = mid;
        else hi = mid;
        if (lo > 0 && hi / lo < 1.002) break;
    }
    try_pack(b, lo, mask, nodes, rects);
    pelt__free(&b->alloc, nodes);
    double area = 0;
    for (size_t p = 0; p < b->patch_count; p++) area += (double)rects[p].w * rects[p].h;
    for (size_t o = 0; o < b->out_count; o++) {
        uint32_t p = b->out_patch[o];
        const float *box = b->patch_box + 4 * p;
        const stbrp_rect *rc = &rects[p];
        float lx = b->out_local[2 * o], ly = b->out_local[2 * o + 1];
        uvs[2 * o] = (float)(((double)rc->x + PELT__ATLAS_GUTTER + (lx - box[0]) * lo) / mask);
        uvs[2 * o + 1] = (float)(((double)rc->y + PELT__ATLAS_GUTTER + (ly - box[1]) * lo) / mask);
    }
    pelt__free(&b->alloc, rects);
    *scale = lo;
    *used = area;
    return PELT_OK;
}
