/* Wet and dry triangles drawn apart (wet_split.h). */
#include "core/wet/wet_split.h"

#include "core/base/hooks.h"

#include <math.h>
#include <string.h>

/* The texel a uv falls in, clamped as the shaders clamp (clump_texel). */
static unsigned texel_of(float uv, unsigned size)
{
    float t = floorf(uv * (float)size);
    if (!(t > 0.0f)) return 0;
    if (t >= (float)(size - 1)) return size - 1;
    return (unsigned)t;
}

bool pelt__wet_split_init(pelt__wet_split *s, const uint32_t *indices, size_t triangle_count,
                          const float *uvs, unsigned width, unsigned height, const pelt_allocator *alloc)
{
    memset(s, 0, sizeof *s);
    s->alloc = *alloc;
    if (width == 0 || height == 0 || width > 65536u || height > 65536u) return false;
    s->box = pelt__alloc(alloc, triangle_count * 4 * sizeof *s->box);
    s->wet = pelt__alloc_zero(alloc, triangle_count ? triangle_count : 1, 1);
    s->indices = pelt__alloc(alloc, triangle_count * 3 * sizeof *s->indices);
    s->source = pelt__alloc(alloc, triangle_count * 3 * sizeof *s->source);
    for (size_t i = 0; i < 3 * triangle_count; i++)
        if (indices[i] >= s->vertex_count) s->vertex_count = (size_t)indices[i] + 1;
    s->vertex_wet = pelt__alloc_zero(alloc, s->vertex_count ? s->vertex_count : 1, 1);
    if ((triangle_count && (!s->box || !s->indices || !s->source)) || !s->wet || !s->vertex_wet) {
        pelt__wet_split_free(s);
        return false;
    }
    s->triangle_count = triangle_count;
    s->mask_width = width, s->mask_height = height;
    s->dry_count = triangle_count;
    if (triangle_count == 0) return true;
    memcpy(s->source, indices, triangle_count * 3 * sizeof *s->source);
    memcpy(s->indices, indices, triangle_count * 3 * sizeof *s->indices);
    for (size_t t = 0; t < triangle_count; t++) {
        unsigned x0 = width, y0 = height, x1 = 0, y1 = 0;
        for (int k = 0; k < 3; k++) {
            const float *uv = uvs + 2 * (size_t)indices[3 * t + k];
            unsigned x = texel_of(uv[0], width), y = texel_of(uv[1], height);
            if (x < x0) x0 = x;
            if (x > x1) x1 = x;
            if (y < y0) y0 = y;
            if (y > y1) y1 = y;
        }
        /* One texel more each way: a vertex's uv on a texel's edge, and
         * interpolation's rounding, may reach into the neighbour. */
        uint16_t *b = s->box + 4 * t;
        b[0] = (uint16_t)(x0 ? x0 - 1 : 0);
        b[1] = (uint16_t)(y0 ? y0 - 1 : 0);
        b[2] = (uint16_t)(x1 + 1 < width ? x1 + 1 : width - 1);
        b[3] = (uint16_t)(y1 + 1 < height ? y1 + 1 : height - 1);
    }
    return true;
}

void pelt__wet_split_free(pelt__wet_split *s)
{
    pelt__free(&s->alloc, s->box);
    pelt__free(&s->alloc, s->wet);
    pelt__free(&s->alloc, s->indices);
    pelt__free(&s->alloc, s->source);
    pelt__free(&s->alloc, s->vertex_wet);
    memset(s, 0, sizeof *s);
}

static bool box_holds_water(const pelt__wet_split *s, const uint16_t *b, const float *texels)
{
    for (unsigned y = b[1]; y <= b[3]; y++) {
        const float *row = texels + ((size_t)y * s->mask_width) * 4;
        for (unsigned x = b[0]; x <= b[2]; x++)
            if (row[4 * x + 3] > 0.0f) return true;
    }
    return false;
}

bool pelt__wet_split_update(pelt__wet_split *s, const float *texels, const unsigned rect[4])
{
    if (rect[0] >= rect[2] || rect[1] >= rect[3]) return false;
    bool changed = false;
    for (size_t t = 0; t < s->triangle_count; t++) {
        const uint16_t *b = s->box + 4 * t;
        if (b[2] < rect[0] || b[0] >= rect[2] || b[3] < rect[1] || b[1] >= rect[3]) continue;
        uint8_t wet = box_holds_water(s, b, texels) ? 1 : 0;
        if (wet != s->wet[t]) {
            s->wet[t] = wet;
            changed = true;
        }
    }
    if (!changed) return false;
    /* Dry triangles from the front, wet ones from the back: one pass. */
    size_t front = 0, back = s->triangle_count;
    memset(s->vertex_wet, 0, s->vertex_count);
    for (size_t t = 0; t < s->triangle_count; t++) {
        size_t at = s->wet[t] ? --back : front++;
        memcpy(s->indices + 3 * at, s->source + 3 * t, 3 * sizeof *s->indices);
        if (s->wet[t])
            for (int k = 0; k < 3; k++) s->vertex_wet[s->source[3 * t + k]] = 1;
    }
    s->dry_count = front;
    return true;
}
