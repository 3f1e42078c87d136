/* Fins (Lengyel et al. 2001 §2.2-2.3) and Kenwright's inter-fur shadows,
 * by what they are for: fins widen the silhouette, fade away where the
 * surface faces the viewer, stay on the strands under a gale, and are one
 * draw call; inter-fur shadows make single hairs stand out on constant-
 * colour fur; wet fins gather their hair into the shells' tufts. */
#include "support/gl_test.h"

#include "core/base/vec.h"
#include "gl/shaders/bindings.glsl"

#include <math.h>
#include <string.h>

enum { W = 240, H = 180 };
#define NPX ((size_t)W * H)
#define DT (1.0f / 60.0f)

static pelt_headless *gl;

static bool covered(const uint8_t *px, size_t i) { return gl_test_coverage(px + 4 * i, 1) == 1; }

/* Covered pixels of `a` within `r` pixels of a covered pixel of `b`. */
static bool near_covered(const uint8_t *b, int x, int y, int r)
{
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++) {
            int xx = x + dx, yy = y + dy;
            if (xx >= 0 && yy >= 0 && xx < W && yy < H && covered(b, (size_t)yy * W + (size_t)xx))
                return true;
        }
    return false;
}

/* The band of pixels within 1..r px outside the covered pixels of `edge`;
 * returns its size, and in *cover how many of them `img` covers. */
static size_t band_cover(const uint8_t *edge, int r, const uint8_t *img, size_t *cover)
{
    size_t band = 0;
    *cover = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (near_covered(edge, x, y, 0) || !near_covered(edge, x, y, r)) continue;
            band++;
            *cover += covered(img, (size_t)y * W + (size_t)x);
        }
    return band;
}

/* How much of `img` the band of `edge` (as band_cover) shows: its
 * pixels' largest channel difference from the background, summed, over
 * 255: a pixel half covered by fins counts about half. */
static double band_amount(const uint8_t *edge, int r, const uint8_t *img)
{
    double amount = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (near_covered(edge, x, y, 0) || !near_covered(edge, x, y, r)) continue;
            amount += gl_test_off_background(img + 4 * ((size_t)y * W + (size_t)x)) / 255.0;
        }
    return amount;
}

typedef struct motion {
    pelt_forces forces;
    float seconds;
} motion;

static void run_motion(pelt_fur *fur, void *user)
{
    const motion *mo = user;
    for (int i = 0; i < (int)(mo->seconds / DT + 0.5f); i++) pelt_fur_step(fur, DT, &mo->forces);
}

static pelt_mesh *torus, *square, *sphere;
static const pelt_camera torus_cam = {30.0f, 25.0f, 3.2f, 40.0f, {0, 0, 0}};

/* (i) A band of 1..6 px just outside the silhouette the shells alone make
 * is background without fins (by construction); fins cover at least a
 * fifth of it. */
static void fins_widen_the_silhouette(void)
{
    const pelt_fur_desc d = {.length = 0.15f};
    const pelt_draw_desc shells = {.no_fins = true};
    uint8_t *a = gl_test_render(gl, torus, &d, &torus_cam, &shells, NULL, NULL);
    uint8_t *b = gl_test_render(gl, torus, &d, &torus_cam, NULL, NULL, NULL);
    CHECK(a && b);
    if (a && b) {
        size_t without, with;
        size_t band = band_cover(a, 6, a, &without);
        band_cover(a, 6, b, &with);
        printf("  band of %zu px outside the shells' silhouette: %zu fur px without fins, %zu with\n",
               band, without, with);
        CHECK(band > 500);
        CHECK(without == 0);
        CHECK(with * 5 >= band);
    }
    free(a);
    free(b);
}

/* The band's pixels' off-background amounts (band_amount's, each over
 * 255): their mean and coefficient of variation. */
static void band_spread(const uint8_t *edge, int r, const uint8_t *img, double *mean, double *cv)
{
    double sum = 0.0, sq = 0.0;
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (near_covered(edge, x, y, 0) || !near_covered(edge, x, y, r)) continue;
            double a = gl_test_off_background(img + 4 * ((size_t)y * W + (size_t)x)) / 255.0;
            sum += a, sq += a * a, n++;
        }
    *mean = n ? sum / (double)n : 0.0;
    double var = n ? sq / (double)n - *mean * *mean : 0.0;
    *cv = *mean > 0.0 ? sqrt(var > 0.0 ? var : 0.0) / *mean : 0.0;
}

/* The outline's hairs (fins.hairs, on by default): where the fur is a few
 * pixels to a few tens long on screen, single hairs cross the outline in
 * place of the fin texture's quads. The band outside the shells' own
 * silhouette holds about as much fur as the quads alone put there (0.5 to
 * 2 times), but as hairs against the background: its pixels vary more
 * from one to the next (coefficient of variation at least 1.15 times the
 * quads'; 1.22 here, and 1 where no hair is drawn). */
static void outline_hairs_cross_the_outline_as_single_hairs(void)
{
    const pelt_fur_desc d = {.length = 0.15f};
    const pelt_draw_desc shells = {.no_fins = true}, quads_only = {.no_outline_hairs = true};
    uint8_t *a = gl_test_render(gl, torus, &d, &torus_cam, &shells, NULL, NULL);
    uint8_t *q = a ? gl_test_render(gl, torus, &d, &torus_cam, &quads_only, NULL, NULL) : NULL;
    uint8_t *h = q ? gl_test_render(gl, torus, &d, &torus_cam, NULL, NULL, NULL) : NULL;
    CHECK(a && q && h);
    if (a && q && h) {
        double mq, cq, mh, ch;
        band_spread(a, 6, q, &mq, &cq);
        band_spread(a, 6, h, &mh, &ch);
        printf("  band outside the shells' silhouette: quads mean %.3f (cv %.2f), hairs mean %.3f (cv %.2f)\n", mq,
               cq, mh, ch);
        CHECK(mh >= 0.5 * mq && mh <= 2.0 * mq);
        CHECK(ch >= 1.15 * cq);
    }
    free(a);
    free(q);
    free(h);
}

/* The hairs take the quads' place only where the fur is a few pixels to
 * a few tens long on screen (outline_share): seen from afar (the fur about
 * 3 px long) and close up (50 to 80 px), the picture is the quads' alone,
 * pixel for pixel. */
static void outline_hairs_leave_far_and_close_views_to_the_quads(void)
{
    const pelt_draw_desc quads_only = {.no_outline_hairs = true};
    const pelt_camera far = {30.0f, 25.0f, 12.0f, 40.0f, {0, 0, 0}}, close = {30.0f, 25.0f, 2.5f, 40.0f, {0, 0, 0}};
    const pelt_fur_desc shorter = {.length = 0.15f}, longer = {.length = 0.8f};
    const struct { const pelt_camera *cam; const pelt_fur_desc *d; } views[2] = {{&far, &shorter}, {&close, &longer}};
    for (int v = 0; v < 2; v++) {
        uint8_t *a = gl_test_render(gl, torus, views[v].d, views[v].cam, NULL, NULL, NULL);
        uint8_t *b = a ? gl_test_render(gl, torus, views[v].d, views[v].cam, &quads_only, NULL, NULL) : NULL;
        CHECK(a && b);
        if (a && b) {
            size_t off = 0, fur = 0;
            for (size_t i = 0; i < NPX; i++) {
                off += memcmp(a + 4 * i, b + 4 * i, 3) != 0;
                fur += covered(a, i);
            }
            printf("  %s: %zu of %zu fur pixels differ from the quads' alone\n", v ? "close" : "far", off, fur);
            CHECK(fur > 500 && off == 0);
        }
        free(a);
        free(b);
    }
}

/* (ii) Seen head-on, a flat furry square renders the same with and without
 * fins (every fin faces away: the fade is 0); at a grazing view fins add
 * coverage above the fur. */
static void fins_fade_head_on_and_show_at_grazing_views(void)
{
    const pelt_fur_desc d = {.length = 0.2f};
    const pelt_camera head_on = {0.0f, 89.0f, 3.0f, 40.0f, {0, 0, 0}};
    const pelt_camera grazing = {0.0f, 6.0f, 3.0f, 40.0f, {0, 0, 0}};
    const pelt_draw_desc shells = {.no_fins = true};
    uint8_t *a = gl_test_render(gl, square, &d, &head_on, &shells, NULL, NULL);
    uint8_t *b = gl_test_render(gl, square, &d, &head_on, NULL, NULL, NULL);
    uint8_t *c = gl_test_render(gl, square, &d, &grazing, &shells, NULL, NULL);
    uint8_t *e = gl_test_render(gl, square, &d, &grazing, NULL, NULL, NULL);
    CHECK(a && b && c && e);
    if (a && b && c && e) {
        double mean, frac;
        gl_test_compare(a, b, NPX, &mean, &frac);
        size_t added = 0;
        for (size_t i = 0; i < NPX; i++) added += covered(e, i) && !covered(c, i);
        printf("  head-on: mean difference %.3f, %.4f of the pixels off by > 32; grazing: fins add %zu px\n",
               mean, frac, added);
        CHECK(mean <= 1.0 && frac <= 0.01); /* the golden tolerance */
        CHECK(added > 200);
    }
    free(a), free(b), free(c), free(e);
}

static motion gale(void)
{
    motion mo = {pelt_forces_default(), 1.0f};
    mo.forces.wind[0] = 60.0f;
    mo.forces.wind[2] = 25.0f;
    mo.forces.gust_strength = 1.0f;
    return mo;
}

/* Fin pixels farther than 3 px from the skin and shells of a render: fins
 * that came apart from the fur. */
static size_t detached(const uint8_t *fins, const uint8_t *fur, size_t *total)
{
    size_t n = 0;
    *total = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (!covered(fins, (size_t)y * W + (size_t)x)) continue;
            (*total)++;
            n += !near_covered(fur, x, y, 3);
        }
    return n;
}

/* (iii) Under a gale the fins bend with the shells: fewer than 1% of the
 * fin pixels lie more than 3 px from the skin and shells. The control
 * draws fins that stayed at rest while the shells blew: they come apart. */
static void fins_stay_on_the_fur_in_a_gale(void)
{
    const pelt_fur_desc d = {.length = 0.25f};
    motion blow = gale(), rest = {pelt_forces_default(), 1.0f};
    const pelt_draw_desc fins_only = {.no_skin = true, .no_outline_hairs = true, .debug.no_shells = true};
    const pelt_draw_desc fur_only = {.no_fins = true};
    uint8_t *fur = gl_test_render(gl, torus, &d, &torus_cam, &fur_only, run_motion, &blow);
    uint8_t *fins = gl_test_render(gl, torus, &d, &torus_cam, &fins_only, run_motion, &blow);
    uint8_t *still = gl_test_render(gl, torus, &d, &torus_cam, &fins_only, run_motion, &rest);
    CHECK(fur && fins && still);
    if (fur && fins && still) {
        size_t total, total_still;
        size_t apart = detached(fins, fur, &total), apart_still = detached(still, fur, &total_still);
        printf("  gale: %zu of %zu fin px off the fur; fins left at rest: %zu of %zu\n", apart, total,
               apart_still, total_still);
        CHECK(total > 500);
        CHECK(apart * 100 < total);
        CHECK(apart_still * 100 >= total_still); /* the check sees fins that come apart */
    }
    free(fur), free(fins), free(still);
}

/* Luminance standard deviation over the pixels covered in both images. */
static double luminance_sd(const uint8_t *px, const uint8_t *mask)
{
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < NPX; i++) {
        if (!covered(mask, i)) continue;
        double l = gl_test_luma(px + 4 * i);
        sum += l, sum2 += l * l, n++;
    }
    if (n < 2) return 0.0;
    double m = sum / (double)n;
    return sqrt(fmax(0.0, sum2 / (double)n - m * m));
}

/* (iv) Constant-colour fur (one colour root to tip, no highlight): with
 * Kenwright's inter-fur shadows the luminance varies at least 1.25 times
 * as much inside the fur: single hairs stand out. Drawn without the tone
 * curve, whose toe would press this dark fur's shades together: what is
 * measured is the shadows, not the curve. */
static void inter_fur_shadows_make_hairs_stand_out(void)
{
    pelt_fur_desc d = {.length = 0.15f,
                       .look = {.color = {0.6f, 0.45f, 0.3f}, .tip_color = {0.6f, 0.45f, 0.3f},
                                .specular = {1e-6f, 1e-6f, 1e-6f}}};
    const pelt_camera cam = {0.0f, 60.0f, 1.6f, 40.0f, {0, 0, 0}};
    const pelt_draw_desc dd = {.tone = PELT_TONE_NONE};
    uint8_t *a = gl_test_render(gl, square, &d, &cam, &dd, NULL, NULL);
    d.look.inter_shadow = true;
    uint8_t *b = gl_test_render(gl, square, &d, &cam, &dd, NULL, NULL);
    CHECK(a && b);
    if (a && b) {
        double sa = luminance_sd(a, a), sb = luminance_sd(b, a);
        printf("  luminance sd inside the fur: %.2f without, %.2f with inter-fur shadows (x%.2f)\n", sa,
               sb, sa > 0 ? sb / sa : 0.0);
        CHECK(sa > 1.0);
        CHECK(sb >= 1.25 * sa);
    }
    free(a), free(b);
}

static size_t chunked(size_t fins) { return (fins + PELT_FIN_CHUNK - 1) / PELT_FIN_CHUNK * PELT_FIN_CHUNK; }

/* Fins closer than the fin texture's slab are fainter by the ratio
 * (pelt__fin_spacing_opacity): where both meshes' edges are shorter than
 * the slab, a sphere modelled with 16 times the triangles puts as much fin
 * into the band outside its shells' silhouette as the coarse one (within
 * 1.25x; 1.19x measured), where fins of full opacity on every short edge
 * stack up (1.76x). */
static void fins_add_up_alike_on_fine_and_coarse_meshes(void)
{
    pelt_mesh *coarse = NULL, *fine = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 24, 12, &coarse, NULL) == PELT_OK);
    CHECK(pelt_mesh_sphere(1.0f, 96, 48, &fine, NULL) == PELT_OK);
    /* A slab of 128 texels: 0.5 fur tiles, longer than both spheres'
     * edges (0.38 and 0.09 tiles long). */
    const pelt_fur_desc d = {.length = 0.15f, .fins.density = 128.0f};
    const pelt_camera cam = {0.0f, 0.0f, 3.4f, 40.0f, {0, 0, 0}};
    const pelt_draw_desc shells = {.no_fins = true}, fins = {.no_outline_hairs = true, .debug.no_shells = true};
    uint8_t *a = coarse && fine ? gl_test_render(gl, coarse, &d, &cam, &shells, NULL, NULL) : NULL;
    uint8_t *fc = a ? gl_test_render(gl, coarse, &d, &cam, &fins, NULL, NULL) : NULL;
    uint8_t *ff = fc ? gl_test_render(gl, fine, &d, &cam, &fins, NULL, NULL) : NULL;
    CHECK(a && fc && ff);
    if (a && fc && ff) {
        size_t with_coarse;
        size_t band = band_cover(a, 5, fc, &with_coarse);
        double in_coarse = band_amount(a, 5, fc), in_fine = band_amount(a, 5, ff);
        printf("  band of %zu px: the coarse sphere's fins cover %zu; fin in it: coarse %.1f px, fine %.1f "
               "(x%.2f)\n",
               band, with_coarse, in_coarse, in_fine, in_coarse > 0.0 ? in_fine / in_coarse : 0.0);
        CHECK(band > 300 && with_coarse * 5 >= band);
        CHECK(in_fine <= 1.25 * in_coarse && in_fine >= 0.8 * in_coarse);
    }
    free(a);
    free(fc);
    free(ff);
    pelt_mesh_destroy(coarse);
    pelt_mesh_destroy(fine);
}

/* A mesh whose edges are shorter than the fin texture's slab draws its
 * fins from a coarser level (pelt__lod_pick_fins): fewer, each less faded
 * by its spacing, they put as much fin into the band outside the shells'
 * silhouette as the full mesh's fins (within 1.25x either way). */
static void fins_from_a_coarser_level_add_up_alike(void)
{
    pelt_mesh *dense = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 192, 96, &dense, NULL) == PELT_OK);
    if (!dense) return;
    /* A slab of 128 texels, half a fur tile: longer than the edges of the
     * torus's first levels. */
    const pelt_fur_desc d = {.length = 0.15f, .fins.density = 128.0f};
    pelt_fur_desc full = d;
    full.lod.mode = PELT_LOD_FIXED; /* mesh level 0 and its own fins */
    const pelt_draw_desc shells = {.no_fins = true}, fins = {.no_outline_hairs = true, .debug.no_shells = true};
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    CHECK(pelt_fur_create(dense, &d, &fur, NULL) == PELT_OK);
    CHECK(fur && pelt_renderer_create(dense, fur, NULL, &r, NULL) == PELT_OK);
    if (r) {
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        v.width = W, v.height = H;
        gl_test_draw_primitives(r, &v, &fins);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        printf("  mesh level %u, fins from level %u (%zu fins)\n", st.mesh_level, st.fin_level, st.fins);
        CHECK(st.fin_level > st.mesh_level);
    }
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
    uint8_t *a = gl_test_render_sized(gl, dense, &d, &torus_cam, &shells, NULL, NULL, true);
    uint8_t *coarse = a ? gl_test_render_sized(gl, dense, &d, &torus_cam, &fins, NULL, NULL, true) : NULL;
    uint8_t *own = coarse ? gl_test_render_sized(gl, dense, &full, &torus_cam, &fins, NULL, NULL, true) : NULL;
    CHECK(a && coarse && own);
    if (a && coarse && own) {
        double in_coarse = band_amount(a, 5, coarse), in_own = band_amount(a, 5, own);
        printf("  fin in the band: from the coarser level %.1f px, from the mesh's own %.1f (x%.2f)\n", in_coarse,
               in_own, in_own > 0.0 ? in_coarse / in_own : 0.0);
        CHECK(in_own > 100.0);
        CHECK(in_coarse <= 1.25 * in_own && in_coarse >= 0.8 * in_own);
    }
    free(a);
    free(coarse);
    free(own);
    pelt_mesh_destroy(dense);
}

/* (vi) One draw call for all fins whatever the mesh; GL's primitive count
 * is the fins' strips, fins x 2 x rows triangles (1..PELT_FIN_ROWS rows,
 * as few as follow the strands). */
static void all_fins_are_one_draw_call(void)
{
    const pelt_mesh *meshes[] = {torus, square, sphere};
    for (int k = 0; k < 3; k++) {
        pelt_fur *fur = NULL;
        pelt_renderer *r = NULL;
        CHECK(pelt_fur_create(meshes[k], &(pelt_fur_desc){.look.texture_size = 32}, &fur, NULL) == PELT_OK);
        CHECK(pelt_renderer_create(meshes[k], fur, NULL, &r, NULL) == PELT_OK);
        if (!r) {
            pelt_fur_destroy(fur);
            continue;
        }
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        const pelt_draw_desc quads = {.no_skin = true, .no_outline_hairs = true, .debug.no_shells = true};
        unsigned prims = gl_test_draw_primitives(r, &v, &quads);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        size_t edges = pelt_mesh_get_data(meshes[k]).triangle_count; /* at least */
        printf("  mesh %d: %u fin draw call(s), %zu fins, %u primitives\n", k, st.fin_draw_calls,
               st.fins, prims);
        /* The fins this view may show (Lengyel: "we collect the fins with
         * nonzero alpha"), one draw. */
        CHECK(st.fin_draw_calls == 1 && st.fins > 0 && st.fins < edges + edges / 2 + 64);
        /* An instance is PELT_FIN_CHUNK strips; the last one's spares collapse. */
        CHECK(st.fin_rows >= 1 && st.fin_rows <= PELT_FIN_ROWS);
        CHECK(prims == chunked(st.fins) * 2 * st.fin_rows);
        /* Unfaded, every fin of the level drawn: still one draw. */
        const pelt_draw_desc unfaded = {.no_skin = true, .debug.no_shells = true, .fins_unfaded = true};
        prims = gl_test_draw_primitives(r, &v, &unfaded);
        pelt_render_stats all = pelt_renderer_get_stats(r);
        CHECK(all.fin_draw_calls == 1 && all.fins >= st.fins);
        CHECK(st.fin_level > 0 || all.fins >= edges);
        CHECK(prims == chunked(all.fins) * 2 * all.fin_rows);
        pelt_renderer_destroy(r);
        pelt_fur_destroy(fur);
    }
}

static void soak_all_over(pelt_fur *fur, void *user)
{
    (void)user;
    pelt_droplet d = {{0.5f, 0.5f}, 0.75f, 1.0f};
    pelt_fur_add_droplet(fur, &d, NULL);
}

/* How much of the band between r0 and r1 px outside the covered pixels of
 * `skin` (square windows, as near_covered) `img` shows, as band_amount. */
static double ring_amount(const uint8_t *skin, int r0, int r1, const uint8_t *img)
{
    double amount = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (near_covered(skin, x, y, r0 - 1) || !near_covered(skin, x, y, r1)) continue;
            amount += gl_test_off_background(img + 4 * ((size_t)y * W + (size_t)x)) / 255.0;
        }
    return amount;
}

/* (v) Wet fins show the shells' tufts from the side (docs/wetness.md,
 * Tufts on the outline): a soaked sphere's fins alone, against the same
 * fins with the tufts held open (tightness 0.01, the same wetness and
 * darkening). Near the skin the roots stay spread: the band 1..3 px out
 * keeps at least 0.9 of its hair; towards the tips the hair gathers into
 * tufts with gaps between: the band at 60-90% of the fur's reach shows at
 * most 0.85 of the open fins' hair. Fins that ignored the clumps would
 * show the same hair in both. */
static void wet_fins_gather_into_tufts(void)
{
    const pelt_camera cam = {0.0f, 0.0f, 3.2f, 40.0f, {0, 0, 0}};
    pelt_fur_desc tufts = {.length = 0.15f}, open = tufts;
    open.wet.clump_tightness = 0.01f;
    const pelt_draw_desc skin_only = {.no_fins = true, .debug.no_shells = true};
    const pelt_draw_desc fins_only = {
        .no_skin = true, .no_outline_hairs = true, .debug.no_shells = true, .fins_unfaded = true};
    uint8_t *skin = gl_test_render(gl, sphere, &tufts, &cam, &skin_only, NULL, NULL);
    uint8_t *a = gl_test_render(gl, sphere, &tufts, &cam, &fins_only, soak_all_over, NULL);
    uint8_t *b = gl_test_render(gl, sphere, &open, &cam, &fins_only, soak_all_over, NULL);
    CHECK(skin && a && b);
    if (skin && a && b) {
        /* The fur's reach in pixels: 0.15 world units at distance 3.2, fov 40. */
        float reach = 0.15f * (float)H / (2.0f * 3.2f * tanf(20.0f * 3.14159265f / 180.0f));
        int r0 = (int)(0.6f * reach + 0.5f), r1 = (int)(0.9f * reach + 0.5f);
        double roots_tufts = ring_amount(skin, 1, 3, a), roots_open = ring_amount(skin, 1, 3, b);
        double tips_tufts = ring_amount(skin, r0, r1, a), tips_open = ring_amount(skin, r0, r1, b);
        printf("  reach %.1f px; roots (1-3 px): %.1f tufted / %.1f open = %.3f; "
               "tips (%d-%d px): %.1f / %.1f = %.3f\n",
               reach, roots_tufts, roots_open, roots_tufts / roots_open, r0, r1, tips_tufts, tips_open,
               tips_tufts / tips_open);
        CHECK(roots_open > 50.0 && tips_open > 20.0);
        CHECK(roots_tufts >= 0.9 * roots_open);
        CHECK(tips_tufts <= 0.85 * tips_open);
    }
    free(skin), free(a), free(b);
}

int main(void)
{
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    gl_test_meshes(&torus, &square);
    CHECK(pelt_mesh_sphere(1.0f, 32, 16, &sphere, NULL) == PELT_OK);
    RUN(fins_widen_the_silhouette);
    RUN(outline_hairs_cross_the_outline_as_single_hairs);
    RUN(outline_hairs_leave_far_and_close_views_to_the_quads);
    RUN(fins_fade_head_on_and_show_at_grazing_views);
    RUN(fins_stay_on_the_fur_in_a_gale);
    RUN(inter_fur_shadows_make_hairs_stand_out);
    RUN(all_fins_are_one_draw_call);
    RUN(fins_add_up_alike_on_fine_and_coarse_meshes);
    RUN(fins_from_a_coarser_level_add_up_alike);
    RUN(wet_fins_gather_into_tufts);
    pelt_mesh_destroy(torus);
    pelt_mesh_destroy(square);
    pelt_mesh_destroy(sphere);
    pelt_headless_destroy(gl);
    return check_summary();
}
