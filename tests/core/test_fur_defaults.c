/* The defaults include/pelt/fur.h states are the ones pelt_fur_get_desc
 * returns: a zero desc on the Table 1 torus, field by field, so the header
 * comments cannot drift from pelt__fur_desc_defaults (core/fur/fur.c). */
#include "support/check.h"

#include "pelt/fur.h"
#include "pelt/mesh.h"

#include <math.h>
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

    CHECK(d.layers == 16);
    CHECK_REL(d.length, 0.03f * diag); /* 3% of the bounding-box diagonal */
    CHECK(d.seed == 1);

    CHECK(d.look.texture_size == 256);
    CHECK_REL(d.look.density, 3000.0f);
    CHECK_REL(d.look.strand_radius, 1.6f);
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
    CHECK_REL(d.wet.darken, 0.35f);
    CHECK(d.wet.clump_size == 0.0f);
    CHECK_REL(d.wet.gloss, 2.0f);
    CHECK_REL(d.wet.gloss_sharpness, 4.0f);

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
    in.seed = 5;
    pelt_fur *fur = m ? fur_on(m, &in) : NULL;
    CHECK(fur != NULL);
    if (fur) {
        pelt_fur_desc d = pelt_fur_get_desc(fur);
        CHECK(d.length == 0.2f && d.dynamics.mass == 2.0f && d.look.tiling == 7.0f && d.seed == 5);
        CHECK_REL(d.dynamics.spring_k, 2.0f * 9.81f / (0.4f * 0.2f));
        CHECK_REL(d.dynamics.damping, 0.5f * sqrtf(d.dynamics.spring_k * 2.0f));
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

int main(void)
{
    RUN(zero_desc_gets_every_documented_default);
    RUN(derived_defaults_follow_the_given_fields);
    return check_summary();
}
