/* The defaults include/pelt/fur.h states are the ones pelt_fur_get_desc
 * returns: a zero desc on the Table 1 torus, field by field, so the header
 * comments cannot drift from pelt__fur_desc_defaults (core/fur/fur.c). */
#include "support/check.h"

#include "pelt/fur.h"
#include "pelt/mesh.h"
#include "pelt/params.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Relative closeness: the header states a formula, the code evaluates it in
 * float. */
#define CHECK_REL(seen, expected) CHECK_NEAR((seen), (expected), 1e-6 * fabs((double)(expected)))

static float bbox_diagonal(const pelt_mesh *m)
{
    float lo[3], hi[3];
    pelt_mesh_bounds(m, lo, hi);
    return sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

static void check_rgb(const float seen[3], float r, float g, float b)
{
    CHECK_REL(seen[0], r);
    CHECK_REL(seen[1], g);
    CHECK_REL(seen[2], b);
}

static pelt_fur *fur_on(const pelt_mesh *m, const pelt_fur_desc *d)
{
    pelt_fur *fur = NULL;
    pelt_error err;
    if (pelt_fur_create(m, d, &fur, &err) != PELT_OK) {
        fprintf(stderr, "  fur: %s\n", err.message);
        return NULL;
    }
    return fur;
}

/* Writes x into a row's field of d (every float of a colour). */
static void put(const pelt_param *p, pelt_fur_desc *d, double x)
{
    unsigned char *f = (unsigned char *)d + p->offset;
    switch (p->type) {
    case PELT_PARAM_UINT: *(unsigned *)(void *)f = (unsigned)x; break;
    case PELT_PARAM_SEED: *(uint32_t *)(void *)f = (uint32_t)x; break;
    case PELT_PARAM_ENUM: *(int *)(void *)f = (int)x; break;
    case PELT_PARAM_BOOL: *(bool *)(void *)f = x != 0.0; break;
    case PELT_PARAM_FLOAT:
        for (unsigned k = 0; k < p->count; k++) ((float *)(void *)f)[k] = (float)x;
        break;
    }
}

/* Every row names a field inside pelt_fur_desc, once; its default (when
 * zero means default) lies in its range; the resolved desc of a zero desc
 * holds that default. */
static void every_row_has_its_default_in_range_and_its_field_in_the_desc(void)
{
    size_t n = 0;
    const pelt_param *rows = pelt_fur_params(&n);
    CHECK(n >= 45);
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 24, 12, &m, NULL) == PELT_OK);
    const pelt_fur_desc zero = {0};
    pelt_fur *fur = m ? fur_on(m, &zero) : NULL;
    pelt_fur_desc d = fur ? pelt_fur_get_desc(fur) : zero;
    for (size_t i = 0; i < n; i++) {
        const pelt_param *p = &rows[i];
        CHECK(pelt_fur_param(p->name) == p);
        CHECK(p->offset < offsetof(pelt_fur_desc, hooks));
        for (size_t j = 0; j < i; j++) CHECK(rows[j].offset != p->offset);
        if (p->derived || !pelt_param_zero_is_default(p)) continue;
        for (unsigned k = 0; k < p->count; k++) {
            double x = p->def[k];
            bool in = ((p->flags & PELT_PARAM_MIN_OPEN) ? x > p->min : x >= p->min) &&
                      ((p->flags & PELT_PARAM_MAX_OPEN) ? x < p->max : x <= p->max);
            if (!in) fprintf(stderr, "  %s: default %g outside its range\n", p->name, x);
            CHECK(in);
            if (p->type == PELT_PARAM_FLOAT)
                CHECK_REL(((const float *)(const void *)((const unsigned char *)&d + p->offset))[k], (float)x);
            else if (p->type == PELT_PARAM_UINT || p->type == PELT_PARAM_SEED)
                CHECK(*(const unsigned *)(const void *)((const unsigned char *)&d + p->offset) == (unsigned)x);
        }
    }
    CHECK(pelt_fur_param("layers") && pelt_fur_param("layers")->def[0] == 32.0);
    CHECK(pelt_fur_param("look.texture_size")->max == 4096.0);
    CHECK(pelt_fur_param("no.such.field") == NULL);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

/* For every bounded row: a value just past either end of its range makes
 * pelt_fur_create fail with a message that names the field. */
static void a_field_just_outside_its_range_is_refused_by_name(void)
{
    size_t n = 0;
    const pelt_param *rows = pelt_fur_params(&n);
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 12, 6, &m, NULL) == PELT_OK);
    size_t tried = 0;
    for (size_t i = 0; m && i < n; i++) {
        const pelt_param *p = &rows[i];
        if (p->type == PELT_PARAM_BOOL || p->type == PELT_PARAM_SEED) continue;
        double outside[2];
        int count = 0;
        if (p->type == PELT_PARAM_ENUM) {
            int names = 0;
            while (p->names[names]) names++;
            outside[count++] = names;
        } else {
            bool integer = p->type == PELT_PARAM_UINT;
            double step = integer ? 1.0 : fmax(1e-3, 1e-3 * fabs(p->max));
            double below = (p->flags & PELT_PARAM_MIN_OPEN) ? p->min : p->min - (integer ? 1.0 : 1e-3);
            /* Zero below the range means "default", and an unsigned cannot go below 0. */
            if (!(below == 0.0 && pelt_param_zero_is_default(p)) && !(integer && below < 0.0) && p->min > -FLT_MAX)
                outside[count++] = below;
            if (p->max < FLT_MAX) outside[count++] = (p->flags & PELT_PARAM_MAX_OPEN) ? p->max : p->max + step;
        }
        for (int c = 0; c < count; c++) {
            pelt_fur_desc d = {0};
            put(p, &d, outside[c]);
            pelt_fur *fur = NULL;
            pelt_error err = {0};
            pelt_status st = pelt_fur_create(m, &d, &fur, &err);
            if (st == PELT_OK || !strstr(err.message, p->name))
                fprintf(stderr, "  %s = %g: status %d, \"%s\"\n", p->name, outside[c], (int)st, err.message);
            CHECK(st == PELT_ERR_INVALID_ARGUMENT && fur == NULL);
            CHECK(strstr(err.message, p->name) != NULL);
            pelt_fur_destroy(fur);
            tried++;
        }
    }
    CHECK(tried >= 40);
    pelt_mesh_destroy(m);
}

static void zero_desc_gets_every_documented_default(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, &m, NULL) == PELT_OK); /* 9,360 triangles */
    const pelt_fur_desc zero = {0};
    pelt_fur *fur = m ? fur_on(m, &zero) : NULL;
    CHECK(fur != NULL);
    if (!fur) {
        pelt_mesh_destroy(m);
        return;
    }
    const float diag = bbox_diagonal(m);
    CHECK(diag > 2.8f && diag < 4.1f); /* the torus's box is 2.8 x 0.8 x 2.8 */
    pelt_fur_desc d = pelt_fur_get_desc(fur);

    CHECK(d.layers == 32); /* straight hair: no curl to add shells for */
    CHECK_REL(d.layers_per_turn, 13.0f);
    CHECK_REL(d.length, 0.03f * diag); /* 3% of the bounding-box diagonal */
    CHECK(d.seed == 1);

    CHECK(d.look.texture_size == 256);
    CHECK(d.lod.texture_taps == 1); /* one fetch a shell fragment */
    CHECK(d.lod.texture_aniso == 4.0f); /* one fetch reads up to 4 texels of a grazing footprint */
    CHECK(d.lod.edge_depth == 16.0f); /* edge-on shells as deep as the hairs */
    CHECK(d.lod.sub_shells == 4); /* close up, up to 4 shells a layer */
    CHECK_REL(d.look.density, 3000.0f);
    CHECK_REL(d.look.strand_radius, 1.6f * (float)d.look.texture_size / 256.0f);
    CHECK_REL(d.look.taper, 0.8f);
    CHECK(d.look.strand_curl == 0.0f && d.look.strand_curl_shape == PELT_STRAND_CURL_HELIX);
    CHECK_REL(d.look.strand_curl_turns, 2.0f);
    CHECK_REL(d.look.tiling, 5.0f / diag);
    check_rgb(d.look.color, 0.55f, 0.34f, 0.18f);
    check_rgb(d.look.tip_color, 1.0f, 0.82f, 0.58f);
    check_rgb(d.look.skin_color, 0.78f, 0.56f, 0.47f);
    CHECK_NEAR(d.fins.length, 1.0f, 0);
    CHECK(!d.look.inter_shadow && d.look.shading == PELT_SHADING_KAJIYA_KAY);
    CHECK_NEAR(d.look.inter_shadow_offset, 4.0f, 0);
    CHECK_NEAR(d.look.inter_shadow_darkness, 0.8f, 0);
    CHECK_NEAR(d.look.diffuse_power, 1.0f, 0);
    CHECK_NEAR(d.fins.density, d.look.texture_size / 16.0f, 0);
    CHECK_NEAR(d.fins.curl, 0.0f, 0);
    CHECK_NEAR(d.fins.curl_turns, 2.0f, 0);
    CHECK_REL(d.look.color_scale, 1.0f);
    check_rgb(d.look.specular, 0.9f, 0.85f, 0.8f);
    CHECK_REL(d.look.shininess, 20.0f);
    CHECK_REL(d.look.shadow, 2.0f);
    CHECK(d.look.curl_frequency == 0.0f);
    CHECK(d.look.curl_radius == 0.0f);
    CHECK(d.look.curl_phase == PELT_CURL_RINGLETS);

    CHECK_REL(d.dynamics.mass, 1.0f);
    CHECK_REL(d.dynamics.spring_k, 1.0f * 9.81f / (0.4f * d.length));
    CHECK_REL(d.dynamics.damping, 0.5f * sqrtf(d.dynamics.spring_k * 1.0f));

    CHECK(d.wet.mask_size == 256);
    CHECK_REL(d.wet.clump_blend, 0.5f);
    CHECK_REL(d.wet.clump_tightness, 0.9f);
    CHECK_REL(d.wet.darken, 0.5f);
    CHECK(d.wet.clumps == PELT_CLUMPS_NATURAL);
    /* Tufts as wide as the fur is long, kept between 20 and 100 hairs. */
    float hairs = d.look.density * d.look.tiling * d.look.tiling;
    CHECK_REL(d.wet.clump_size, fminf(fmaxf(d.length, sqrtf(20.0f / hairs)), sqrtf(100.0f / hairs)));
    CHECK_REL(d.wet.gloss, 2.0f);
    CHECK_REL(d.wet.gloss_sharpness, 8.0f);
    CHECK_REL(d.wet.weight, 1.0f);
    CHECK_REL(d.wet.clump_lean, 0.3f);
    CHECK(d.wet.lie == 0.0f); /* wet fur keeps its comb unless asked (docs/wetness.md) */

    CHECK(d.comb.slant == 0.0f);

    /* Zero hooks mean malloc/free and silence (pelt/base.h): kept as zero. */
    const pelt_hooks no_hooks = {0};
    CHECK(memcmp(&d.hooks, &no_hooks, sizeof no_hooks) == 0);

    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

static void derived_defaults_follow_the_given_fields(void)
{
    /* spring_k and damping default from the mass and length in force,
     * given or defaulted; given fields are kept as they are. */
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, 4, &m, NULL) == PELT_OK);
    pelt_fur_desc in = {0};
    in.length = 0.2f;
    in.dynamics.mass = 2.0f;
    in.look.tiling = 7.0f;
    in.look.texture_size = 64; /* small: the texture is made here */
    in.seed = 5;
    pelt_fur *fur = m ? fur_on(m, &in) : NULL;
    CHECK(fur != NULL);
    if (fur) {
        pelt_fur_desc d = pelt_fur_get_desc(fur);
        CHECK(d.length == 0.2f && d.dynamics.mass == 2.0f && d.look.tiling == 7.0f && d.seed == 5);
        CHECK_REL(d.dynamics.spring_k, 2.0f * 9.81f / (0.4f * 0.2f));
        CHECK_REL(d.dynamics.damping, 0.5f * sqrtf(d.dynamics.spring_k * 2.0f));
        /* The same hair at every texture size: 1.6 texels at 256, 0.4 at 64. */
        CHECK_REL(d.look.strand_radius, 0.4f);
        pelt_fur_destroy(fur);
    }
    /* With nothing given, the length is 3% of this mesh's own diagonal. */
    const pelt_fur_desc zero = {0};
    fur = m ? fur_on(m, &zero) : NULL;
    CHECK(fur != NULL);
    if (fur) {
        CHECK_REL(pelt_fur_get_desc(fur).length, 0.03f * bbox_diagonal(m));
        CHECK_REL(pelt_fur_get_desc(fur).look.tiling, 5.0f / bbox_diagonal(m));
        pelt_fur_destroy(fur);
    }
    pelt_mesh_destroy(m);
}

static unsigned layers_of(pelt_mesh *m, const pelt_fur_desc *in)
{
    pelt_fur *fur = fur_on(m, in);
    CHECK(fur != NULL);
    unsigned layers = fur ? pelt_fur_get_desc(fur).layers : 0;
    pelt_fur_destroy(fur);
    return layers;
}

static void curled_hair_takes_its_shells_a_turn(void)
{
    /* layers is the count edge-on for hair that does not curl; a curl of
     * T turns takes ceil(T layers_per_turn) where that is more. */
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, 4, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt_fur_desc in = {0};
    in.look.texture_size = 32; /* small: the texture is made here */
    in.length = 0.1f;
    /* Silva Fig. 7's presets: one turn (wavy), two, six. */
    const struct {
        const char *preset;
        unsigned layers;
    } looks[] = {{"straight", 32}, {"wavy", 32}, {"few-large-curls", 32}, {"many-small-curls", 78}};
    for (size_t i = 0; i < sizeof looks / sizeof looks[0]; i++) {
        pelt_fur_desc d = in;
        CHECK(pelt_fur_desc_curl_preset(&d, m, looks[i].preset, NULL) == PELT_OK);
        unsigned seen = layers_of(m, &d);
        if (seen != looks[i].layers) fprintf(stderr, "  %s: %u layers\n", looks[i].preset, seen);
        CHECK(seen == looks[i].layers);
    }
    /* Given layers stay where they are already enough, and the turns of
     * the texture's own curl count with Silva's. */
    pelt_fur_desc d = in;
    CHECK(pelt_fur_desc_curl_preset(&d, m, "many-small-curls", NULL) == PELT_OK);
    d.layers = 96;
    CHECK(layers_of(m, &d) == 96);
    d.layers = 16;
    d.layers_per_turn = 4.0f;
    CHECK(layers_of(m, &d) == 24);
    d.layers_per_turn = 1.0f;
    CHECK(layers_of(m, &d) == 16);
    d = in;
    d.look.strand_curl = 6.0f;
    d.look.strand_curl_turns = 3.0f;
    CHECK(layers_of(m, &d) == 39);
    d.look.curl_frequency = 6.2831853f * 2.5f; /* coherent or ringlets alike */
    d.look.curl_radius = 0.01f;
    CHECK(layers_of(m, &d) == 72);
    /* Never past the 256 a fur may have. */
    d.look.strand_curl_turns = 32.0f;
    CHECK(layers_of(m, &d) == 256);
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(curled_hair_takes_its_shells_a_turn);
    RUN(zero_desc_gets_every_documented_default);
    RUN(derived_defaults_follow_the_given_fields);
    RUN(every_row_has_its_default_in_range_and_its_field_in_the_desc);
    RUN(a_field_just_outside_its_range_is_refused_by_name);
    return check_summary();
}
