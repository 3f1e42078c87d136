/* Wet and dry triangles drawn apart (core/wet/wet_split.h): a triangle
 * called dry reads no water anywhere it covers, the partition holds every
 * triangle once, and the flags follow the mask as it wets and dries. */
#include "support/check.h"
#include "core/base/hooks.h"
#include "core/wet/wet_split.h"
#include "pelt/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MASK = 64 };

static float texel_rho(const float *texels, float u, float v)
{
    int x = (int)floorf(u * MASK), y = (int)floorf(v * MASK);
    x = x < 0 ? 0 : x >= MASK ? MASK - 1 : x;
    y = y < 0 ? 0 : y >= MASK ? MASK - 1 : y;
    return texels[((size_t)y * MASK + (size_t)x) * 4 + 3];
}

/* Water on the texels within r of (cu, cv) (wet 1) or taken off (0). */
static void paint_disc(float *texels, float cu, float cv, float r, float wet)
{
    for (int y = 0; y < MASK; y++)
        for (int x = 0; x < MASK; x++) {
            float u = (x + 0.5f) / MASK - cu, v = (y + 0.5f) / MASK - cv;
            if (u * u + v * v <= r * r) texels[((size_t)y * MASK + (size_t)x) * 4 + 3] = wet;
        }
}

/* Every point of every triangle called dry (a barycentric grid, corners
 * included) reads rho = 0; some triangle is wet exactly where water is. */
static void check_split(const pelt__wet_split *s, const pelt_mesh_data *m, const float *texels, size_t *wet_out)
{
    size_t wet = 0;
    for (size_t t = 0; t < s->triangle_count; t++) {
        const float *a = m->uvs + 2 * m->indices[3 * t], *b = m->uvs + 2 * m->indices[3 * t + 1],
                    *c = m->uvs + 2 * m->indices[3 * t + 2];
        bool water = false;
        for (int i = 0; i <= 8; i++)
            for (int j = 0; i + j <= 8; j++) {
                float wa = i / 8.0f, wb = j / 8.0f, wc = 1.0f - wa - wb;
                float u = wa * a[0] + wb * b[0] + wc * c[0], v = wa * a[1] + wb * b[1] + wc * c[1];
                if (texel_rho(texels, u, v) > 0.0f) water = true;
            }
        if (water) CHECK(s->wet[t] == 1);
        wet += s->wet[t];
    }
    CHECK(s->dry_count + wet == s->triangle_count);
    /* The partition: the dry part holds exactly the dry triangles' indices
     * (their sum; each triangle is copied whole). */
    unsigned long long dry_sum = 0, part_dry = 0;
    for (size_t t = 0; t < s->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            if (!s->wet[t]) dry_sum += m->indices[3 * t + k];
            if (t < s->dry_count) part_dry += s->indices[3 * t + k];
        }
    CHECK(dry_sum == part_dry);
    /* A vertex is wet exactly where a wet triangle has it (the fins' ends). */
    CHECK(s->vertex_count == m->vertex_count);
    size_t bad_vertex = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        bool at_wet = false;
        for (size_t t = 0; t < s->triangle_count; t++)
            for (int k = 0; k < 3; k++) at_wet |= s->wet[t] && m->indices[3 * t + k] == v;
        bad_vertex += s->vertex_wet[v] != at_wet;
    }
    CHECK(bad_vertex == 0);
    *wet_out = wet;
}

static void split_follows_the_water(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_square(2.0f, 16, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    pelt_mesh_data m = pelt_mesh_get_data(mesh);
    float *texels = calloc((size_t)MASK * MASK * 4, sizeof *texels);
    pelt_allocator alloc = {0};
    pelt__wet_split s;
    CHECK(texels && pelt__wet_split_init(&s, m.indices, m.triangle_count, m.uvs, MASK, MASK, &alloc));
    size_t wet = 0;
    if (texels && s.triangle_count) {
        CHECK(s.dry_count == m.triangle_count);
        /* A drop: its triangles go to the wet part, the rest stay dry. */
        paint_disc(texels, 0.3f, 0.3f, 0.1f, 1.0f);
        const unsigned all[4] = {0, 0, MASK, MASK};
        CHECK(pelt__wet_split_update(&s, texels, all));
        check_split(&s, &m, texels, &wet);
        printf("  one drop: %zu of %zu triangles wet\n", wet, s.triangle_count);
        CHECK(wet > 0 && wet < s.triangle_count / 4);
        /* A rectangle far from the water changes nothing. */
        const unsigned far[4] = {50, 50, 60, 60};
        CHECK(!pelt__wet_split_update(&s, texels, far));
        /* A second drop, told by its own rectangle only. */
        paint_disc(texels, 0.75f, 0.7f, 0.08f, 1.0f);
        const unsigned second[4] = {42, 39, 54, 51};
        CHECK(pelt__wet_split_update(&s, texels, second));
        size_t wet2 = 0;
        check_split(&s, &m, texels, &wet2);
        CHECK(wet2 > wet);
        /* Drying the first returns its triangles to the dry part. */
        paint_disc(texels, 0.3f, 0.3f, 0.1f, 0.0f);
        const unsigned first[4] = {12, 12, 27, 27};
        CHECK(pelt__wet_split_update(&s, texels, first));
        size_t wet3 = 0;
        check_split(&s, &m, texels, &wet3);
        CHECK(wet3 < wet2 && wet3 > 0);
        paint_disc(texels, 0.75f, 0.7f, 0.08f, 0.0f);
        CHECK(pelt__wet_split_update(&s, texels, all));
        CHECK(s.dry_count == s.triangle_count);
        size_t still_wet = 0; /* dried, every vertex dry again */
        for (size_t v = 0; v < s.vertex_count; v++) still_wet += s.vertex_wet[v];
        CHECK(still_wet == 0);
    }
    pelt__wet_split_free(&s);
    free(texels);
    pelt_mesh_destroy(mesh);
}

static void init_refuses_a_mask_it_cannot_index(void)
{
    const uint32_t tri[3] = {0, 1, 2};
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    pelt_allocator alloc = {0};
    pelt__wet_split s;
    CHECK(!pelt__wet_split_init(&s, tri, 1, uvs, 0, 16, &alloc));
    CHECK(!pelt__wet_split_init(&s, tri, 1, uvs, 70000, 16, &alloc));
    CHECK(pelt__wet_split_init(&s, tri, 1, uvs, 16, 16, &alloc));
    pelt__wet_split_free(&s);
}

int main(void)
{
    RUN(split_follows_the_water);
    RUN(init_refuses_a_mask_it_cannot_index);
    return check_summary();
}
