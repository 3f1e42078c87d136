/* Images rendered on Mesa llvmpipe headless: golden references under a
 * tolerance, and properties that need no reference. */
#include "support/gl_test.h"

#include "gl/gpu.h"
#include "gl/passes.h"

enum { W = 160, H = 120 };

static pelt_headless *gl;
static pelt_mesh *torus, *square;
static const pelt_camera torus_cam = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
static const pelt_camera square_cam = {20.0f, 40.0f, 3.2f, 40.0f, {0, 0, 0}};

static void golden_torus_default_fur(void)
{
    pelt_fur_desc d = {0};
    uint8_t *px = gl_test_render(gl, torus, &d, &torus_cam, NULL, NULL, NULL);
    CHECK(px != NULL);
    if (px) gl_test_golden("torus", px, W, H, 4.0, 0.03);
    free(px);
}

static void golden_square_default_fur(void)
{
    pelt_fur_desc d = {0};
    uint8_t *px = gl_test_render(gl, square, &d, &square_cam, NULL, NULL, NULL);
    CHECK(px != NULL);
    if (px) gl_test_golden("square", px, W, H, 4.0, 0.03);
    free(px);
}

/* Fur reaches beyond the bare mesh's silhouette: pixels covered with
 * shells that the skin alone leaves as background. */
static void fur_covers_beyond_bare_silhouette(void)
{
    pelt_fur_desc d = {0};
    pelt_draw_desc bare = {.debug.no_shells = true, .no_fins = true};
    uint8_t *skin = gl_test_render(gl, torus, &d, &torus_cam, &bare, NULL, NULL);
    uint8_t *fur = gl_test_render(gl, torus, &d, &torus_cam, NULL, NULL, NULL);
    CHECK(skin && fur);
    if (skin && fur) {
        size_t n = (size_t)W * H, outside = 0;
        for (size_t i = 0; i < n; i++)
            if (gl_test_coverage(skin + 4 * i, 1) == 0 && gl_test_coverage(fur + 4 * i, 1) == 1)
                outside++;
        size_t bare_cov = gl_test_coverage(skin, n);
        printf("  bare coverage %zu px, fur adds %zu px outside it\n", bare_cov, outside);
        CHECK(outside > bare_cov / 50);
    }
    free(skin);
    free(fur);
}

static void longer_fur_covers_more(void)
{
    pelt_fur_desc shorter = {.length = 0.06f}, longer = {.length = 0.18f};
    uint8_t *a = gl_test_render(gl, torus, &shorter, &torus_cam, NULL, NULL, NULL);
    uint8_t *b = gl_test_render(gl, torus, &longer, &torus_cam, NULL, NULL, NULL);
    CHECK(a && b);
    if (a && b) {
        size_t ca = gl_test_coverage(a, (size_t)W * H), cb = gl_test_coverage(b, (size_t)W * H);
        printf("  coverage: length 0.06 -> %zu px, length 0.18 -> %zu px\n", ca, cb);
        CHECK(cb > ca + ca / 50);
    }
    free(a);
    free(b);
}

/* All shells go out in one instanced draw, whatever the layer count; the
 * primitives GL generated prove every layer was drawn by it. */
static void shells_are_one_instanced_draw(void)
{
    const unsigned layer_counts[] = {1, 16, 64};
    for (size_t k = 0; k < 3; k++) {
        pelt_fur_desc d = {.layers = layer_counts[k]};
        pelt_fur *fur = NULL;
        pelt_renderer *r = NULL;
        pelt_draw_desc shells_only = {.no_skin = true, .no_fins = true, .debug.no_view_split = true};
        CHECK(pelt_fur_create(torus, &d, &fur, NULL) == PELT_OK);
        CHECK(pelt_renderer_create(torus, fur, NULL, &r, NULL) == PELT_OK);
        if (!r) {
            pelt_fur_destroy(fur);
            continue;
        }
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        unsigned prims = gl_test_draw_primitives(r, &v, &shells_only);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        CHECK(st.shell_draw_calls == 1);
        CHECK(st.skin_draw_calls == 0);
        CHECK(st.shell_instances == layer_counts[k]);
        CHECK(st.triangles == (size_t)9360 * layer_counts[k]);
        CHECK_NEAR(prims, 9360.0 * layer_counts[k], 0.0);
        pelt_renderer_destroy(r);
        pelt_fur_destroy(fur);
    }
}

/* pelt bench --plain's yardstick: one instanced draw of every layer over the
 * full mesh (nothing culled: the torus is closed and would cull its back
 * faces with fins), and its fur reaches past the bare silhouette. */
static void plain_renderer_draws_every_shell(void)
{
    pelt_fur_desc d = {.layers = 16};
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    CHECK(pelt_fur_create(torus, &d, &fur, NULL) == PELT_OK);
    CHECK(pelt_renderer_create(torus, fur, NULL, &r, NULL) == PELT_OK);
    if (r) {
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        pelt_draw_desc plain = {.no_skin = true, .no_fins = true, .debug.plain_shells = true};
        unsigned prims = gl_test_draw_primitives(r, &v, &plain);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        CHECK(st.shell_draw_calls == 1 && st.fin_draw_calls == 0);
        CHECK(st.shell_instances == 16);
        CHECK_NEAR(prims, 9360.0 * 16, 0.0);
    }
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);

    pelt_draw_desc bare = {.debug.no_shells = true, .no_fins = true};
    pelt_draw_desc plain = {.no_fins = true, .debug.plain_shells = true};
    uint8_t *skin = gl_test_render(gl, torus, &d, &torus_cam, &bare, NULL, NULL);
    uint8_t *fur_px = gl_test_render(gl, torus, &d, &torus_cam, &plain, NULL, NULL);
    CHECK(skin && fur_px);
    if (skin && fur_px) {
        size_t n = (size_t)W * H, outside = 0;
        for (size_t i = 0; i < n; i++)
            if (gl_test_coverage(skin + 4 * i, 1) == 0 && gl_test_coverage(fur_px + 4 * i, 1) == 1) outside++;
        printf("  the plain shells cover %zu px outside the bare skin's %zu\n", outside, gl_test_coverage(skin, n));
        CHECK(outside > gl_test_coverage(skin, n) / 50);
    }
    free(skin);
    free(fur_px);
}

static void wet_left_half(pelt_fur *fur, void *user)
{
    (void)user;
    /* Rain-sized droplets over u < 0.5 only: each makes a clump (Silva
     * §3.1), overlapping ones merge or overwrite as Alg. 1 says. */
    pelt_rain r = {0.0f, 0.03f, 0.05f, 1.0f, 1.0f, 7};
    pelt_fur_add_random_droplets(fur, &r, 300);
    /* Dry the right half again with a hair dryer: negative droplets. */
    for (float v = 0.0f; v <= 1.0f; v += 0.02f)
        for (float u = 0.52f; u <= 1.0f; u += 0.02f) {
            pelt_droplet d = {{u, v}, 0.03f, -1.0f};
            pelt_fur_add_droplet(fur, &d, NULL);
        }
    for (float v = 0.0f; v <= 1.0f; v += 0.02f) {
        pelt_droplet d = {{0.5f + 0.03f, v}, 0.035f, -1.0f};
        pelt_fur_add_droplet(fur, &d, NULL);
    }
}

/* The torus's default fur, wet by `wet` (NULL: dry) before its renderer
 * is made (*fur NULL, and NULL returned, where either fails). */
static pelt_renderer *torus_renderer(void (*wet)(pelt_fur *, void *), pelt_fur **fur)
{
    pelt_fur_desc d = {0};
    pelt_renderer *r = NULL;
    *fur = NULL;
    CHECK(pelt_fur_create(torus, &d, fur, NULL) == PELT_OK);
    if (*fur && wet) wet(*fur, NULL);
    CHECK(*fur && pelt_renderer_create(torus, *fur, NULL, &r, NULL) == PELT_OK);
    return r;
}

/* The torus soaked all over: 1500 drops of 0.05-0.08 (mask uv). */
static void soak(pelt_fur *fur, void *user)
{
    (void)user;
    const pelt_rain rain = {0.0f, 0.05f, 0.08f, 1.0f, 1.0f, 11};
    pelt_fur_add_random_droplets(fur, &rain, 1500);
}

/* One frame of r from v with d over the test background, read into px. */
static void draw_and_read(pelt_renderer *r, const pelt_view *v, const pelt_draw_desc *d, uint8_t *px)
{
    pelt_headless_bind(gl);
    glClearColor(gl_test_background[0], gl_test_background[1], gl_test_background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_renderer_draw(r, v, d);
    pelt_headless_read_rgba8(gl, px);
}

/* A frame drawn in parts (by view or by wetness) against the same frame
 * drawn whole: within mean 0.1 and 0.2% of pixels off by more than 32
 * (triangles where the parts overlap on screen may blend in another order
 * within a shell). */
static void check_apart_matches_together(const uint8_t *apart, const uint8_t *together, const char *what)
{
    double mean, frac;
    gl_test_compare(apart, together, (size_t)W * H, &mean, &frac);
    printf("  %s: mean %.3f, %.4f of pixels off by more than 32\n", what, mean, frac);
    CHECK(mean < 0.1 && frac < 0.002);
}

/* The view split's test on the torus, dry or wet on its left half
 * (wet_left_half): from its camera and from nearly edge-on, the picture
 * with the split against the one with it off (debug.no_view_split), within
 * check_apart_matches_together's bounds; split faces some triangles face-on
 * and draws `per_shell` draws a shell (more than 2, at most 4, when 0),
 * the reference `reference_per_shell` (0: one draw). */
static void view_split_matches(bool wet, unsigned per_shell, unsigned reference_per_shell, const char *what)
{
    pelt_fur *fur;
    pelt_renderer *r = torus_renderer(wet ? wet_left_half : NULL, &fur);
    uint8_t *apart = malloc((size_t)W * H * 4), *together = malloc((size_t)W * H * 4);
    for (int view = 0; view < 2 && r && apart && together; view++) {
        pelt_camera cam = torus_cam;
        if (view == 1) cam.pitch = 4.0f; /* degrees: nearly edge-on */
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&cam, (float)W / H, &v);
        pelt_draw_desc split = {0}, whole = {.debug.no_view_split = true};
        draw_and_read(r, &v, &split, apart);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        printf("  view %d: %zu of %zu triangles face-on, %u shell draws for %u shells\n", view,
               st.face_on_triangles, st.mesh_triangles, st.shell_draw_calls, st.shell_instances);
        CHECK(st.face_on_triangles > 0 && st.face_on_triangles < st.mesh_triangles);
        CHECK(st.shell_instances > 1);
        if (per_shell)
            CHECK(st.shell_draw_calls == per_shell * st.shell_instances);
        else
            CHECK(st.shell_draw_calls > 2 * st.shell_instances && st.shell_draw_calls <= 4 * st.shell_instances);
        draw_and_read(r, &v, &whole, together);
        st = pelt_renderer_get_stats(r);
        CHECK(st.face_on_triangles == 0);
        CHECK(st.shell_draw_calls == (reference_per_shell ? reference_per_shell * st.shell_instances : 1));
        check_apart_matches_together(apart, together, what);
    }
    free(apart);
    free(together);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
}

/* Face-on and side-on drawn apart (the view split): dry fur draws the
 * triangles none of whose vertices see the surface from the side without
 * the read across the gap, a shell at a time (two draws a shell), and the
 * picture is the one every triangle drawn with the read gives, within the
 * wet split's bounds (a shell's triangles where the two parts overlap on
 * screen may blend in another order). A view from the side splits anew. */
static void face_on_and_side_on_drawn_apart(void)
{
    view_split_matches(false, 2, 0, "apart against one program");
}

/* A wet frame drawn apart is split by the view too: the dry part's and
 * the wet part's face-on triangles each without the read across the gap
 * (up to four shell draws a shell), and the picture is the one the wet
 * split alone gives (two draws a shell). */
static void wet_and_dry_each_drawn_apart_by_the_view(void)
{
    view_split_matches(true, 0, 2, "apart by the view against the wet split alone");
}

/* pelt bench's dry frame in a wet run (pelt_draw_debug.as_dry): the wet
 * fur drawn with the dry shaders (no wet program, no wet fins) is the
 * picture of the same fur towelled dry (nothing stepped between: the same
 * strands), and far from the wet one. */
static void wet_fur_drawn_as_dry_is_the_towelled_picture(void)
{
    pelt_fur *fur;
    pelt_renderer *r = torus_renderer(soak, &fur);
    uint8_t *as_dry = malloc((size_t)W * H * 4), *other = malloc((size_t)W * H * 4);
    if (r && as_dry && other) {
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        pelt_draw_desc dry = {.debug.as_dry = true}, drawn = {0};
        draw_and_read(r, &v, &dry, as_dry);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        /* The dry frame's view split, two draws a shell; soaked, the wet
         * frame is two draws: the layers below the tufts' base, the rest. */
        CHECK(st.shell_draw_calls == 2 * st.shell_instances && st.face_on_triangles > 0);
        draw_and_read(r, &v, &drawn, other);
        CHECK(pelt_renderer_get_stats(r).shell_draw_calls == 2);
        double wet_mean, towelled_mean, frac;
        gl_test_compare(as_dry, other, (size_t)W * H, &wet_mean, &frac);
        pelt_fur_clear_wetness(fur);
        draw_and_read(r, &v, &drawn, other);
        gl_test_compare(as_dry, other, (size_t)W * H, &towelled_mean, &frac);
        printf("  drawn dry against drawn wet: mean %.3f; against towelled dry: mean %.3f\n", wet_mean,
               towelled_mean);
        CHECK(towelled_mean < 0.5 * wet_mean);
        check_apart_matches_together(as_dry, other, "drawn dry against towelled dry");
    }
    free(as_dry);
    free(other);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
}

/* The wet layers below the tufts' base (pelt__clump_below_tufts), where a
 * clump leaves its hairs where they grew, draw with the lean wet program
 * (no clump lookup, the free hair's light): a soaked torus takes two
 * shell draws, the base layers and the rest, against one with every layer
 * drawn with the tufts' program (debug.no_tuft_base), and the pictures
 * differ by a mean under 0.1 of 255 with under 0.1% of pixels off by more
 * than 32; so does a torus wet on one half, drawn apart. */
static void wet_layers_below_the_tufts_base_drawn_lean(void)
{
    void (*wetness[2])(pelt_fur *, void *) = {soak, wet_left_half};
    for (int k = 0; k < 2; k++) {
        pelt_fur *fur;
        pelt_renderer *r = torus_renderer(wetness[k], &fur);
        uint8_t *lean = malloc((size_t)W * H * 4), *full = malloc((size_t)W * H * 4);
        if (r && lean && full) {
            pelt_view v;
            memset(&v, 0, sizeof v);
            pelt_camera_to_view(&torus_cam, (float)W / H, &v);
            pelt_draw_desc drawn = {0}, tufts = {.debug.no_tuft_base = true};
            draw_and_read(r, &v, &drawn, lean);
            unsigned lean_draws = pelt_renderer_get_stats(r).shell_draw_calls;
            draw_and_read(r, &v, &tufts, full);
            unsigned full_draws = pelt_renderer_get_stats(r).shell_draw_calls;
            if (k == 0) CHECK(lean_draws == 2 && full_draws == 1);
            double mean, frac;
            gl_test_compare(lean, full, (size_t)W * H, &mean, &frac);
            printf("  %s: %u and %u shell draws, mean %.3f, %.4f of pixels off by more than 32\n",
                   k == 0 ? "soaked" : "wet on one half", lean_draws, full_draws, mean, frac);
            CHECK(mean < 0.1 && frac < 0.001);
        }
        free(lean);
        free(full);
        pelt_renderer_destroy(r);
        pelt_fur_destroy(fur);
    }
}

/* Wet and dry drawn apart: a torus wet on one half draws its dry triangles
 * with the dry shader (two shell draws a shell, dry then wet), its fins
 * with both ends dry with the dry fin shader (two fin draws), and the
 * picture is the one every triangle drawn wet gives, within mean 0.1 and
 * 0.2% of pixels off by more than 32: within a shell, triangles where the
 * two parts overlap on screen may blend in another order (two instanced
 * draws, all dry shells then all wet, were 0.23 and 0.35% off here).
 * Every triangle drawn wet, two draws (below the tufts' base and above).
 * Towelled dry, one draw; wet again elsewhere, the triangles follow. */
static void wet_and_dry_drawn_apart(void)
{
    pelt_fur *fur;
    pelt_renderer *r = torus_renderer(wet_left_half, &fur);
    uint8_t *apart = malloc((size_t)W * H * 4), *together = malloc((size_t)W * H * 4);
    if (r && apart && together) {
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        v.light = (pelt_light){{0.5f, 1.0f, 0.8f}, {1.5f, 1.45f, 1.4f}, 0.25f};
        pelt_draw_desc split = {.debug.no_view_split = true}, whole = {.debug.no_wet_split = true};
        draw_and_read(r, &v, &split, apart);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        CHECK(st.shell_instances > 1 && st.shell_draw_calls == 2 * st.shell_instances);
        CHECK(st.fin_draw_calls == 2); /* the fins too: dry, then wet */
        draw_and_read(r, &v, &whole, together);
        /* Every triangle wet: the layers below the tufts' base, then the rest. */
        CHECK(pelt_renderer_get_stats(r).shell_draw_calls == 2);
        CHECK(pelt_renderer_get_stats(r).fin_draw_calls == 1);
        check_apart_matches_together(apart, together, "apart against together");
        /* Towelled dry, then wet where it had been dry (the front of the
         * ring): the triangles follow the mask's changed rectangles. */
        pelt_fur_clear_wetness(fur);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        pelt_renderer_draw(r, &v, &split);
        CHECK(pelt_renderer_get_stats(r).shell_draw_calls == 1);
        CHECK(pelt_renderer_get_stats(r).fin_draw_calls == 1);
        for (float u = 0.6f; u < 0.95f; u += 0.05f) {
            pelt_droplet drop = {{u, 0.25f}, 0.05f, 1.0f};
            pelt_fur_add_droplet(fur, &drop, NULL);
        }
        draw_and_read(r, &v, &split, apart);
        st = pelt_renderer_get_stats(r);
        CHECK(st.shell_instances > 1 && st.shell_draw_calls == 2 * st.shell_instances);
        draw_and_read(r, &v, &whole, together);
        check_apart_matches_together(apart, together, "wet again elsewhere");
    }
    free(apart);
    free(together);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Luminance below which `frac` of the fur pixels of columns [x0, x1) lie. */
static double luma_percentile(const uint8_t *px, int x0, int x1, double frac)
{
    static double v[W * H];
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * W + (size_t)x);
            if (gl_test_coverage(p, 1)) v[n++] = gl_test_luma(p);
        }
    if (n == 0) return 0.0;
    qsort(v, n, sizeof v[0], cmp_double);
    return v[(size_t)(frac * (double)(n - 1))];
}

/* Fraction of the fur pixels of columns [x0, x1) darker than `level`. */
static double dark_fraction(const uint8_t *px, int x0, int x1, double level)
{
    size_t dark = 0, n = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * W + (size_t)x);
            if (!gl_test_coverage(p, 1)) continue;
            n++;
            if (gl_test_luma(p) < level) dark++;
        }
    return n ? (double)dark / (double)n : 0.0;
}

static double mean_diff_in(const uint8_t *a, const uint8_t *b, int x0, int x1)
{
    double s = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++)
            for (int k = 0; k < 3; k++) {
                size_t i = 4 * ((size_t)y * W + (size_t)x) + (size_t)k;
                s += fabs((double)a[i] - (double)b[i]);
            }
    return s / (3.0 * (double)(x1 - x0) * H);
}

static void one_droplet_in_the_middle(pelt_fur *fur, void *user)
{
    (void)user;
    pelt_droplet drop = {{0.5f, 0.5f}, 0.06f, 1.0f};
    pelt_fur_add_droplet(fur, &drop, NULL);
}

/* The same at a grazing angle, where the fur in front of a wet patch hangs
 * over it on screen: long fur on the square with one droplet, seen from
 * 25 degrees above its plane. Drawn as two instanced draws, every dry
 * shell and then every wet one, the wet patch's inner shells lay over the
 * tips of the dry fur in front of it (dark rectangles, mean 3.3 and 5% of
 * pixels off); a shell at a time they keep the order of one draw. */
static void wet_and_dry_drawn_apart_at_a_grazing_angle(void)
{
    const pelt_camera cam = {0.0f, 25.0f, 1.0f, 30.0f, {0.0f, 0.05f, 0.0f}};
    pelt_fur_desc d = {.length = 0.15f, .layers = 32, .wet.clumps = PELT_CLUMPS_DROPLET};
    pelt_draw_desc whole = {.debug.no_wet_split = true};
    uint8_t *apart = gl_test_render(gl, square, &d, &cam, NULL, one_droplet_in_the_middle, NULL);
    uint8_t *together = gl_test_render(gl, square, &d, &cam, &whole, one_droplet_in_the_middle, NULL);
    CHECK(apart && together);
    if (apart && together) {
        check_apart_matches_together(apart, together, "apart against together");
    }
    free(apart);
    free(together);
}

/* Clumps open gaps (Silva Fig. 8, 13): seen at an angle, dry fur hides
 * the skin; wet fur gathered into clumps shows skin and shadowed roots
 * between them. "Skin-coloured" = darker than the darkest tenth of the
 * dry fur in the same place; wet darkening is off so only the clump
 * geometry counts. The dry half of the square must render as before. */
static void wet_clumps_show_skin_and_leave_dry_fur_alone(void)
{
    /* Looking along -Z at the square, u along x. */
    const pelt_camera cam = {0.0f, 35.0f, 2.6f, 45.0f, {0, 0, 0}};
    pelt_fur_desc d = {.wet.darken = 1e-6f, .wet.clumps = PELT_CLUMPS_DROPLET};
    uint8_t *dry = gl_test_render(gl, square, &d, &cam, NULL, NULL, NULL);
    uint8_t *wet = gl_test_render(gl, square, &d, &cam, NULL, wet_left_half, NULL);
    CHECK(dry && wet);
    if (dry && wet) {
        double left = mean_diff_in(dry, wet, 0, W / 2), right = mean_diff_in(dry, wet, W / 2, W);
        /* The wet half is the one that changed; look away from the middle. */
        int wet_is_left = left > right;
        int wx0 = wet_is_left ? W / 8 : W / 2 + W / 8, wx1 = wx0 + W / 4;
        int dx0 = wet_is_left ? W / 2 + W / 8 : W / 8, dx1 = dx0 + W / 4;
        double level = luma_percentile(dry, wx0, wx1, 0.10);
        double dark_dry = dark_fraction(dry, wx0, wx1, level);
        double dark_wet = dark_fraction(wet, wx0, wx1, level);
        double dry_half = mean_diff_in(dry, wet, dx0, dx1);
        printf("  halves changed by %.2f (left) / %.2f (right); skin-coloured fraction of the "
               "wet half: dry %.3f, wet %.3f; dry half changed by %.3f\n",
               left, right, dark_dry, dark_wet, dry_half);
        CHECK(dark_wet > 2.0 * dark_dry + 0.05);
        CHECK(dry_half < 0.5);
    }
    free(dry);
    free(wet);
}

static void wet_then_dry(pelt_fur *fur, void *user)
{
    (void)user;
    wet_left_half(fur, NULL);
    /* Dry at 0.5 per second for 3 s with no forces (tips stay at rest). */
    pelt_forces none = pelt_forces_default();
    none.gravity[1] = 0.0f;
    pelt_fur_set_dry_rate(fur, 0.5f);
    for (int i = 0; i < 180; i++) pelt_fur_step(fur, 1.0f / 60.0f, &none);
}

/* Dried to zero wetness, the fur renders as if it had never been wet:
 * clumps open and curls come back (Silva §1). */
static void dried_fur_matches_dry_render(void)
{
    const pelt_camera cam = {0.0f, 35.0f, 2.6f, 45.0f, {0, 0, 0}};
    pelt_fur_desc d = {.look.curl_frequency = 12.0f, .look.curl_radius = 0.02f};
    uint8_t *dry = gl_test_render(gl, square, &d, &cam, NULL, NULL, NULL);
    uint8_t *wet = gl_test_render(gl, square, &d, &cam, NULL, wet_left_half, NULL);
    uint8_t *dried = gl_test_render(gl, square, &d, &cam, NULL, wet_then_dry, NULL);
    CHECK(dry && wet && dried);
    if (dry && wet && dried) {
        double was = mean_diff_in(dry, wet, 0, W), now = mean_diff_in(dry, dried, 0, W);
        printf("  mean difference from the dry render: wet %.3f, dried %.3f\n", was, now);
        CHECK(was > 2.0);
        CHECK(now < 0.05);
    }
    free(dry);
    free(wet);
    free(dried);
}

static void one_big_clump(pelt_fur *fur, void *user)
{
    (void)user;
    /* One clump over the whole square. */
    pelt_droplet d = {{0.5f, 0.5f}, 0.75f, 1.0f};
    pelt_fur_add_droplet(fur, &d, NULL);
}

/* Distance from the image centre within which 90% of the covered pixels
 * lie. */
static double covered_radius90(const uint8_t *px)
{
    static double r[W * H];
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (gl_test_coverage(px + 4 * ((size_t)y * W + (size_t)x), 1))
                r[n++] = hypot(x + 0.5 - W / 2.0, y + 0.5 - H / 2.0);
    if (n == 0) return 0.0;
    qsort(r, n, sizeof r[0], cmp_double);
    return r[(size_t)(0.9 * (double)(n - 1))];
}

/* At full wetness a clump narrows from root to tip (Silva Fig. 9, 13):
 * seen from above one layer at a time, the fur of one clump covering the
 * whole square gathers into an ever smaller disc around its centre, while
 * dry fur covers the square at every height. */
static void clumps_grow_thinner_toward_the_tips(void)
{
    const pelt_camera top = {0.0f, 89.0f, 2.4f, 50.0f, {0, 0, 0}};
    pelt_fur_desc d = {.layers = 16, .wet.clump_tightness = 1.0f, .wet.darken = 1e-6f,
                       .wet.clumps = PELT_CLUMPS_DROPLET, .wet.strays = 1e-6f};
    const unsigned layers[] = {1, 4, 7, 10};
    double dry_r[4], wet_r[4];
    for (int k = 0; k < 4; k++) {
        pelt_draw_desc one = {.no_skin = true, .no_fins = true, .first_layer = layers[k], .layer_count = 1};
        uint8_t *dry = gl_test_render(gl, square, &d, &top, &one, NULL, NULL);
        uint8_t *wet = gl_test_render(gl, square, &d, &top, &one, one_big_clump, NULL);
        CHECK(dry && wet);
        dry_r[k] = dry ? covered_radius90(dry) : 0.0;
        wet_r[k] = wet ? covered_radius90(wet) : 0.0;
        printf("  layer %2u of 16: 90%% of the fur within %5.1f px dry, %5.1f px clumped\n",
               layers[k], dry_r[k], wet_r[k]);
        free(dry);
        free(wet);
    }
    for (int k = 1; k < 4; k++) CHECK(wet_r[k] < wet_r[k - 1]);
    CHECK(wet_r[3] < 0.6 * wet_r[0]);
    CHECK(dry_r[3] > 0.9 * dry_r[0]);
}

static void wet_all_over(pelt_fur *fur, void *user)
{
    float rho = *(const float *)user;
    pelt_droplet d = {{0.5f, 0.5f}, 0.75f, rho};
    if (rho > 0.0f) pelt_fur_add_droplet(fur, &d, NULL);
}

/* Renders `mesh` evenly wet at rho 0, 0.5 and 1 (wet_all_over) and gives
 * the brightest 0.2% of each picture (a highlight's peak) and its median. */
static void peak_by_wetness(const pelt_mesh *mesh, const pelt_fur_desc *d, const pelt_camera *cam,
                            const pelt_draw_desc *dd, const char *what, double peak[3], double median[3])
{
    const float wetness[] = {0.0f, 0.5f, 1.0f};
    for (int k = 0; k < 3; k++) {
        float rho = wetness[k];
        uint8_t *px = gl_test_render(gl, mesh, d, cam, dd, wet_all_over, &rho);
        CHECK(px != NULL);
        peak[k] = px ? luma_percentile(px, 0, W, 0.998) : 0.0;
        median[k] = px ? luma_percentile(px, 0, W, 0.5) : 0.0;
        printf("  wetness %.1f: %s peak %.1f, median %.1f\n", (double)rho, what, peak[k], median[k]);
        free(px);
    }
}

/* Wet fur looks wet (docs/wetness.md, Wet shine): the square of combed fur
 * evenly wet at rising wetness, the clumps held open (tightness ~0) so that
 * only the shading changes. The highlight's peak (the brightest 0.2% of the
 * fur) rises with the wetness while the fur as a whole (its median) darkens. */
static void wet_fur_highlight_peak_rises_with_wetness(void)
{
    pelt_fur_desc d = {.wet.clump_tightness = 1e-6f, .look.specular = {0.3f, 0.3f, 0.3f},
                       .comb.slant = 60.0f};
    /* Seen from -X, the camera's rays meet the strands (combed 60 degrees
     * along +X) near the cone of mirror directions of the light. */
    const pelt_camera cam = {-90.0f, 25.0f, 2.6f, 45.0f, {0, 0, 0}};
    double peak[3], median[3];
    peak_by_wetness(square, &d, &cam, NULL, "highlight", peak, median);
    CHECK(peak[1] > peak[0] + 3.0 && peak[2] > peak[1] + 3.0);
    CHECK(median[2] < median[0]);
}

/* Wet skin carries the water film's sheen (docs/wetness.md, Wet optics):
 * the torus's skin alone, evenly wet at rising wetness. Where the skin
 * mirrors the light a highlight appears and rises with the wetness (the
 * brightest 0.2% of the picture), while the skin as a whole darkens (its
 * median); dry skin has none. */
static void wet_skin_sheen_rises_with_wetness(void)
{
    const pelt_fur_desc d = {0};
    const pelt_draw_desc skin_only = {.no_fins = true, .debug.no_shells = true};
    double peak[3], median[3];
    peak_by_wetness(torus, &d, &torus_cam, &skin_only, "skin highlight", peak, median);
    CHECK(peak[1] > peak[0] + 10.0 && peak[2] > peak[1] + 5.0);
    CHECK(median[2] <= median[0]);
}

/* Ringlets (docs/method.md): water takes the curl out. Square fur curled
 * as ringlets, evenly wet with the clumps held open and wet shading off,
 * renders soaked as the same fur without curl; half wet, between that and
 * the dry ringlets. The shells, then the fins alone (every fin unfaded):
 * the fin texture holds the same ringlet levels as the fur volume. */
static void soaked_ringlets_render_as_straight_fur(void)
{
    const pelt_camera cam = {0.0f, 35.0f, 2.6f, 45.0f, {0, 0, 0}};
    pelt_fur_desc curly = {.look.curl_frequency = 12.566371f, .look.curl_radius = 0.03f,
                           .wet = {.clump_tightness = 1e-6f, .darken = 1e-6f, .gloss = 1.0f,
                                   .gloss_sharpness = 1.0f}};
    pelt_fur_desc straight = curly;
    straight.look.curl_radius = 0.0f;
    float dry = 0.0f, half = 0.5f, soaked = 1.0f;
    const pelt_draw_desc passes[2] = {{.no_fins = true},
                                      {.no_skin = true, .debug.no_shells = true, .fins_unfaded = true}};
    const char *names[2] = {"shells", "fins"};
    for (int k = 0; k < 2; k++) {
        const pelt_draw_desc *dd = &passes[k];
        uint8_t *c0 = gl_test_render(gl, square, &curly, &cam, dd, wet_all_over, &dry);
        uint8_t *c5 = gl_test_render(gl, square, &curly, &cam, dd, wet_all_over, &half);
        uint8_t *c1 = gl_test_render(gl, square, &curly, &cam, dd, wet_all_over, &soaked);
        uint8_t *s1 = gl_test_render(gl, square, &straight, &cam, dd, wet_all_over, &soaked);
        CHECK(c0 && c5 && c1 && s1);
        if (c0 && c5 && c1 && s1) {
            double d_dry = mean_diff_in(c0, s1, 0, W), d_half = mean_diff_in(c5, s1, 0, W);
            double d_soaked = mean_diff_in(c1, s1, 0, W);
            printf("  %s: mean difference from straight fur: dry ringlets %.3f, half wet %.3f, soaked %.3f\n",
                   names[k], d_dry, d_half, d_soaked);
            CHECK(d_dry > 3.0);
            CHECK(d_half < 0.8 * d_dry && d_half > d_soaked);
            CHECK(d_soaked < 0.3);
        }
        free(c0), free(c5), free(c1), free(s1);
    }
}

/* Blobs of covered pixels (4-connected) of at least `min_px` pixels. */
static size_t count_blobs(const uint8_t *px, size_t min_px)
{
    static int label[W * H], stack[W * H];
    memset(label, 0, sizeof label);
    size_t blobs = 0;
    for (int s = 0; s < W * H; s++) {
        if (label[s] || !gl_test_coverage(px + 4 * (size_t)s, 1)) continue;
        size_t size = 0, top = 0;
        label[s] = 1;
        stack[top++] = s;
        while (top) {
            int i = stack[--top], x = i % W, y = i / W;
            size++;
            const int nb[4] = {x > 0 ? i - 1 : -1, x < W - 1 ? i + 1 : -1, y > 0 ? i - W : -1,
                               y < H - 1 ? i + W : -1};
            for (int k = 0; k < 4; k++)
                if (nb[k] >= 0 && !label[nb[k]] && gl_test_coverage(px + 4 * (size_t)nb[k], 1)) {
                    label[nb[k]] = 1;
                    stack[top++] = nb[k];
                }
        }
        if (size >= min_px) blobs++;
    }
    return blobs;
}

static void soak_square(pelt_fur *fur, void *user)
{
    (void)user;
    pelt_droplet d = {{0.5f, 0.5f}, 0.75f, 1.0f};
    pelt_fur_add_droplet(fur, &d, NULL);
}

/* Sub shells (docs/wetness.md, Sub shells): long fur on the soaked
 * square seen close, its tufts large on screen. Just above a tuft's base
 * a hair at its rim moves several pixels from one layer to the next and
 * was drawn as a dotted line; those layers' wet shells are now drawn as
 * sub shells. Each takes its share of the layer's coverage, so the fur
 * keeps its brightness (mean luminance within 2%), and the dots join: the
 * difference between neighbouring pixels over the fur falls (by 9% here,
 * bound 5%). Seen from afar, where a tuft is a few pixels, there are none. */
static void sub_shells_join_a_tufts_hairs(void)
{
    pelt_fur_desc d = {.length = 0.3f, .wet = {.clump_tightness = 1.0f, .clump_size = 0.4f, .strays = 1e-6f}};
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    CHECK(pelt_fur_create(square, &d, &fur, NULL) == PELT_OK);
    if (fur) soak_square(fur, NULL);
    CHECK(fur && pelt_renderer_create(square, fur, NULL, &r, NULL) == PELT_OK);
    const pelt_camera close = {20.0f, 50.0f, 1.1f, 40.0f, {0, 0, 0}}, afar = {20.0f, 50.0f, 12.0f, 40.0f, {0, 0, 0}};
    uint8_t *px[2] = {malloc((size_t)W * H * 4), malloc((size_t)W * H * 4)};
    unsigned sub[2] = {0, 0};
    if (r && px[0] && px[1]) {
        pelt_view v;
        memset(&v, 0, sizeof v);
        v.light = (pelt_light){{0.5f, 1.0f, 0.8f}, {1.5f, 1.45f, 1.4f}, 0.25f};
        pelt_draw_desc dd[2] = {{.debug.no_sub_shells = true}, {0}};
        for (int k = 0; k < 2; k++) {
            pelt_camera_to_view(&close, (float)W / H, &v);
            v.width = W, v.height = H; /* the sub shells measure tufts in pixels */
            draw_and_read(r, &v, &dd[k], px[k]);
            sub[k] = pelt_renderer_get_stats(r).sub_shells;
        }
        double lum[2] = {0, 0}, step[2] = {0, 0};
        size_t n = 0;
        for (int y = 0; y + 1 < H; y++)
            for (int x = 0; x + 1 < W; x++) {
                size_t i = (size_t)y * W + (size_t)x;
                if (gl_test_coverage(px[0] + 4 * i, 1) == 0 && gl_test_coverage(px[1] + 4 * i, 1) == 0) continue;
                n++;
                for (int k = 0; k < 2; k++) {
                    const uint8_t *p = px[k] + 4 * i;
                    double l = gl_test_luma(p);
                    lum[k] += l;
                    step[k] += fabs(l - gl_test_luma(p + 4)) + fabs(l - gl_test_luma(p + 4 * W));
                }
            }
        for (int k = 0; k < 2; k++) lum[k] /= (double)(n ? n : 1), step[k] /= (double)(n ? n : 1);
        pelt_camera_to_view(&afar, (float)W / H, &v);
        v.width = W, v.height = H;
        pelt_renderer_draw(r, &v, &dd[1]);
        unsigned sub_afar = pelt_renderer_get_stats(r).sub_shells;
        printf("  close: %u sub shells; luminance %.2f without, %.2f with; neighbour step %.2f -> %.2f over %zu px;"
               " afar %u sub shells\n", sub[1], lum[0], lum[1], step[0], step[1], n, sub_afar);
        CHECK(sub[0] == 0 && sub[1] > 0 && sub_afar == 0);
        CHECK(n > (size_t)W * H / 4);
        CHECK(fabs(lum[1] - lum[0]) < 0.02 * lum[0]);
        CHECK(step[1] < 0.95 * step[0]);
        char path[1024];
        snprintf(path, sizeof path, "%s/sub_shells_off.png", PELT_TEST_OUT);
        stbi_write_png(path, W, H, 4, px[0], W * 4);
        snprintf(path, sizeof path, "%s/sub_shells_on.png", PELT_TEST_OUT);
        stbi_write_png(path, W, H, 4, px[1], W * 4);
    }
    free(px[0]);
    free(px[1]);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
}

/* Natural clumps (docs/wetness.md): the square soaked by one droplet and
 * seen from above, its outer four shells alone: Silva's one clump per
 * droplet draws one tuft; clumps of a size draw separate pointed tufts,
 * about area / clump_size^2 of them, four times as many at half the size. */
static void soaked_square_makes_tufts_by_clump_size(void)
{
    const pelt_camera top = {0.0f, 89.0f, 2.4f, 50.0f, {0, 0, 0}};
    pelt_draw_desc tips = {.no_skin = true, .no_fins = true, .first_layer = 12, .layer_count = 4};
    const float sizes[] = {0.0f, 0.5f, 0.25f};
    size_t tufts[3];
    for (int k = 0; k < 3; k++) {
        pelt_fur_desc d = {.layers = 16, .length = 0.12f,
                           .wet = {.clump_tightness = 1.0f, .clump_size = sizes[k], .strays = 1e-6f,
                                   .clumps = sizes[k] > 0.0f ? PELT_CLUMPS_NATURAL : PELT_CLUMPS_DROPLET}};
        uint8_t *px = gl_test_render(gl, square, &d, &top, &tips, soak_square, NULL);
        CHECK(px != NULL);
        tufts[k] = px ? count_blobs(px, 3) : 0;
        char path[1024];
        snprintf(path, sizeof path, "%s/tufts_%d.png", PELT_TEST_OUT, k);
        if (px) stbi_write_png(path, W, H, 4, px, W * 4);
        printf("  clump size %.2f: %zu tufts (area / size^2 = %.0f)\n", (double)sizes[k], tufts[k],
               sizes[k] > 0.0f ? 4.0 / ((double)sizes[k] * sizes[k]) : 1.0);
        free(px);
    }
    CHECK(tufts[0] == 1);
    CHECK(tufts[1] >= 12 && tufts[1] <= 20);
    CHECK(tufts[2] >= 3 * tufts[1]);
}

/* Soaked, then dried for *user seconds at 0.25 a second, no forces but
 * the drying (no gravity: every state's strands stand alike). */
static void soak_then_dry(pelt_fur *fur, void *user)
{
    soak_square(fur, NULL);
    pelt_forces calm = pelt_forces_default();
    calm.gravity[1] = 0.0f;
    pelt_fur_set_dry_rate(fur, 0.25f);
    for (float t = *(const float *)user; t > 0.0f; t -= 0.5f) pelt_fur_step(fur, fminf(t, 0.5f), &calm);
}

/* Coverage of one layer band of the square seen from above (no skin, no
 * fins), as a share of the pixels; `blobs` gets its separate pieces. */
static double band_coverage(const pelt_fur_desc *d, unsigned first, unsigned count, float dried_for, size_t *blobs)
{
    const pelt_camera top = {0.0f, 89.0f, 2.4f, 50.0f, {0, 0, 0}};
    /* Each layer's coverage whole: the tufts' layout is measured, not how
     * the shells share a hair that several of them show. */
    pelt_draw_desc band = {.no_skin = true, .no_fins = true, .first_layer = first, .layer_count = count,
                           .debug = {.no_overcount = true}};
    uint8_t *px = dried_for < 0.0f ? gl_test_render(gl, square, d, &top, &band, NULL, NULL)
                                   : gl_test_render(gl, square, d, &top, &band, soak_then_dry, &dried_for);
    CHECK(px != NULL);
    if (!px) return 0.0;
    double c = (double)gl_test_coverage(px, (size_t)W * H) / (double)(W * H);
    if (blobs) *blobs = count_blobs(px, 3);
    free(px);
    return c;
}

/* Tufts, not dishes (docs/wetness.md, Tufts): the soaked square seen from
 * above, one layer at a time (wet darkening off, so that coverage counts
 * hair, not its colour). Low down the hair stays where it grew: each of the
 * lowest quarter of the layers covers at least 0.9 of what the same dry
 * layer covers (Eq. 5 read from the root left the rim of every clump bald
 * there). Towards the tips the tufts gather: layer 13 of 16 (the dry
 * fur's last with solid hair; the tips above taper out) covers less than
 * 0.8 of the dry one's (the tufts' hair is denser but the gaps between
 * them are bare), in at least 10 separate tufts. */
static void tufts_keep_their_roots_and_gather_at_the_tips(void)
{
    pelt_fur_desc d = {.layers = 16, .length = 0.12f, .wet = {.clump_size = 0.4f, .darken = 1e-6f}};
    double worst_low = INFINITY;
    for (unsigned n = 0; n < 4; n++) {
        double dry = band_coverage(&d, n, 1, -1.0f, NULL), wet = band_coverage(&d, n, 1, 0.0f, NULL);
        printf("  layer %u of 16: coverage dry %.3f, soaked %.3f\n", n + 1, dry, wet);
        worst_low = fmin(worst_low, wet / fmax(dry, 1e-9));
    }
    size_t tufts = 0;
    double dry_top = band_coverage(&d, 12, 1, -1.0f, NULL), wet_top = band_coverage(&d, 12, 1, 0.0f, &tufts);
    printf("  lowest quarter: soaked / dry at least %.3f; layer 13 of 16: dry %.3f, soaked %.3f in %zu tufts\n",
           worst_low, dry_top, wet_top, tufts);
    CHECK(worst_low >= 0.9);
    CHECK(wet_top < 0.8 * dry_top);
    CHECK(tufts >= 10);
}

/* Drying loosens the tufts (docs/wetness.md): the soaked square drying at
 * 0.25 a second, seen from above with wet darkening and shine off, so that
 * only the tufts' shape tells it from dry fur. At every step of a second
 * the picture is nearer the dry fur's (mean difference falling), and dry,
 * it is the dry fur's. */
static void drying_loosens_the_tufts_step_by_step(void)
{
    const pelt_camera top = {0.0f, 60.0f, 2.4f, 50.0f, {0, 0, 0}};
    pelt_fur_desc d = {.layers = 16, .length = 0.12f,
                       .wet = {.clump_size = 0.4f, .darken = 1e-6f, .gloss = 1.0f, .gloss_sharpness = 1.0f}};
    uint8_t *dry = gl_test_render(gl, square, &d, &top, NULL, NULL, NULL);
    CHECK(dry != NULL);
    double prev = INFINITY;
    bool falling = true;
    for (int k = 0; dry && k <= 4; k++) {
        float t = (float)k;
        uint8_t *px = gl_test_render(gl, square, &d, &top, NULL, soak_then_dry, &t);
        CHECK(px != NULL);
        double diff = px ? mean_diff_in(dry, px, 0, W) : INFINITY;
        printf("  dried for %d s (wetness %.2f): mean difference from dry fur %.3f\n", k, 1.0 - 0.25 * k, diff);
        falling = falling && diff < prev;
        prev = diff;
        free(px);
    }
    CHECK(falling);
    CHECK(prev < 0.1);
    free(dry);
}

/* The tufts shine (docs/wetness.md, Tuft light): the combed square, evenly
 * wet and clumped, seen near the mirror cone of the light; the tufts held
 * to one shape (tightness s = 0.45 / rho keeps the pull s rho) and wet
 * darkening off, so that only the water's shine changes: the brightest
 * 0.2% of the picture, the tufts' highlights, rises with the wetness. */
static void tuft_highlight_rises_with_wetness(void)
{
    const pelt_camera cam = {-90.0f, 25.0f, 2.6f, 45.0f, {0, 0, 0}};
    const float wetness[] = {0.5f, 0.75f, 1.0f};
    double peak[3];
    for (int k = 0; k < 3; k++) {
        float rho = wetness[k];
        pelt_fur_desc d = {.look.specular = {0.3f, 0.3f, 0.3f}, .comb.slant = 60.0f,
                           .wet = {.clump_size = 0.3f, .clump_tightness = 0.45f / rho, .darken = 1e-6f}};
        pelt_draw_desc shells = {.no_fins = true};
        uint8_t *px = gl_test_render(gl, square, &d, &cam, &shells, wet_all_over, &rho);
        CHECK(px != NULL);
        peak[k] = px ? luma_percentile(px, 0, W, 0.998) : 0.0;
        printf("  wetness %.2f, clumped: highlight peak %.1f\n", (double)rho, peak[k]);
        free(px);
    }
    /* Smaller steps than the open fur's above: the tufts' tangents spread
     * the highlight over many directions. */
    CHECK(peak[1] > peak[0] + 1.0 && peak[2] > peak[1] + 1.0);
}

/* Counts what the renderer's allocator hooks see. */
typedef struct counting_allocator {
    size_t allocs, frees;
} counting_allocator;

static void *count_alloc(size_t size, void *user)
{
    ((counting_allocator *)user)->allocs++;
    return malloc(size);
}

static void count_free(void *ptr, void *user)
{
    ((counting_allocator *)user)->frees++;
    free(ptr);
}

/* The desc's allocator makes and frees everything the renderer allocates
 * (itself and the temporary vertex arrays); a half-set allocator is refused. */
static void renderer_allocates_through_its_hooks(void)
{
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    CHECK(pelt_fur_create(square, &(pelt_fur_desc){.look.texture_size = 32}, &fur, NULL) == PELT_OK);
    counting_allocator counts = {0, 0};
    pelt_renderer_desc rd = {.hooks.allocator = {count_alloc, count_free, &counts}};
    CHECK(pelt_renderer_create(square, fur, &rd, &r, NULL) == PELT_OK);
    /* The renderer, the two interleaved vertex arrays (the pose's and the
     * rest's, freed before return), the mip chains of the fin texture and
     * the fur volume (one slice's at a time, freed before return), the
     * staging of the fins a frame draws, of their vertices and of the
     * outline's hairs, the wet split's five arrays (its triangles'
     * boxes, flags, indices twice, and its vertices' flags) and the view
     * split's three (its indices, this frame's, its vertices' scratch). */
    CHECK(counts.allocs == 16);
    CHECK(counts.frees == 4);
    pelt_renderer_destroy(r);
    CHECK(counts.allocs == counts.frees);
    pelt_renderer_desc half = {.hooks.allocator = {count_alloc, NULL, &counts}};
    pelt_error err = {0};
    r = NULL;
    CHECK(pelt_renderer_create(square, fur, &half, &r, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(r == NULL);
    pelt_fur_destroy(fur);
}

static void log_into(pelt_log_level level, const char *message, void *user)
{
    if (level == PELT_LOG_ERROR) snprintf(user, 512, "%s", message);
}

/* An allocator that refuses everything once `refuse` is set. */
static void *refusing_alloc(size_t size, void *user)
{
    return *(bool *)user ? NULL : malloc(size);
}

static void refusing_free(void *ptr, void *user)
{
    (void)user;
    free(ptr);
}

/* An allocator that refuses its `fail_at`-th allocation (from 0). */
typedef struct failing_allocator {
    int count, fail_at, live;
} failing_allocator;

static void *failing_alloc(size_t size, void *user)
{
    failing_allocator *f = user;
    if (f->count++ == f->fail_at) return NULL;
    f->live++;
    return malloc(size);
}

static void failing_free(void *ptr, void *user)
{
    if (ptr) ((failing_allocator *)user)->live--;
    free(ptr);
}

/* Whichever allocation of the renderer's creation fails (the mip chains'
 * scratch included), it says out of memory and gives everything back;
 * only the wet split, which saves time, does without (every triangle then
 * draws wet) and the renderer is made. */
static void renderer_creation_survives_each_failed_allocation(void)
{
    pelt_fur *fur = NULL;
    CHECK(pelt_fur_create(square, &(pelt_fur_desc){.look.texture_size = 32}, &fur, NULL) == PELT_OK);
    int refused = 0, failed = 0, done = 0;
    for (int n = 0; n < 64 && !done; n++) {
        failing_allocator f = {0, n, 0};
        pelt_renderer_desc rd = {.hooks.allocator = {failing_alloc, failing_free, &f}};
        pelt_renderer *r = NULL;
        pelt_error err = {0};
        pelt_status st = pelt_renderer_create(square, fur, &rd, &r, &err);
        done = f.count <= n; /* every allocation made: nothing was refused */
        refused += !done;
        if (st == PELT_OK) {
            CHECK(r != NULL);
            pelt_renderer_destroy(r);
        } else {
            failed++;
            CHECK(st == PELT_ERR_OUT_OF_MEMORY && r == NULL);
            CHECK(strstr(err.message, "memory") != NULL);
        }
        CHECK(f.live == 0);
    }
    printf("  %d allocations refused one at a time: %d creations failed, out of memory\n", refused, failed);
    CHECK(done);
    CHECK(refused >= 12 && failed >= 7 && failed < refused);
    pelt_fur_destroy(fur);
}

/* A strand reference that cannot be drawn says so in the stats as well as
 * the log, so that a caller (pelt compare, pelt render --strands) stops
 * instead of taking the skin alone for the hairs: here its hairs find no
 * memory. With memory the same frame draws them and fails nothing. */
static void strand_reference_failure_is_reported(void)
{
    pelt_fur *fur = NULL;
    CHECK(pelt_fur_create(square, &(pelt_fur_desc){.look.texture_size = 32}, &fur, NULL) == PELT_OK);
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(&square_cam, (float)W / H, &v);
    const pelt_draw_desc strands = {.mode = PELT_DRAW_STRANDS};
    for (int with_memory = 0; with_memory < 2; with_memory++) {
        bool refuse = false;
        char logged[512] = "";
        pelt_renderer_desc rd = {.hooks = {.allocator = {refusing_alloc, refusing_free, &refuse},
                                           .logger = {log_into, logged}}};
        pelt_renderer *r = NULL;
        CHECK(pelt_renderer_create(square, fur, &rd, &r, NULL) == PELT_OK);
        if (!r) continue;
        refuse = !with_memory;
        pelt_renderer_draw(r, &v, &strands);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        if (with_memory) {
            CHECK(st.strand_failures == 0 && st.strand_draw_calls == 1 && st.strands > 0);
        } else {
            CHECK(st.strand_failures == 1 && st.strand_draw_calls == 0);
            CHECK(strstr(logged, "out of memory for the strand reference") != NULL);
            /* It stays failed: the next frame does not draw half of it. */
            pelt_renderer_draw(r, &v, &strands);
            CHECK(pelt_renderer_get_stats(r).strand_failures == 1);
        }
        refuse = false;
        pelt_renderer_destroy(r);
    }
    pelt_fur_destroy(fur);
}

/* A shader that does not compile reaches the logger as well as the error. */
static void program_errors_reach_the_logger(void)
{
    char logged[512] = "";
    pelt_hooks hooks = {.logger = {log_into, logged}};
    const char *vs[] = {"void main() { gl_Position = vec4(0.0); }\n", NULL};
    const char *fs[] = {"out vec4 o; void main() { o = not_declared; }\n", NULL};
    GLuint p = 0;
    pelt_error err = {0};
    CHECK(pelt__gl_program_create("broken", vs, fs, &hooks, &p, &err) == PELT_ERR_GL);
    CHECK(p == 0);
    CHECK(strstr(logged, "broken fragment shader does not compile") != NULL);
    CHECK(strcmp(logged, err.message) == 0);
    pelt__gl_state_reset();
}

/* The shell variants a frame can ask for compile: each drawing feature
 * alone and with water, everything with the vertex stage's skinning, and
 * the light pass with every mix of what it keeps (water, ringlets,
 * skinning). A light-pass variant that does not compile leaves the fur out
 * of the shadow maps with nothing but a log line to say so. */
static void every_shell_variant_compiles(void)
{
    char logged[512] = "";
    pelt_hooks hooks = {.logger = {log_into, logged}};
    pelt__shell_pass pass;
    CHECK(pelt__shell_pass_create(&pass, &hooks, NULL) == PELT_OK);
    unsigned asked[64], n = 0;
    for (unsigned bit = 1; bit < PELT__SHELL_LIGHT_PASS; bit <<= 1) {
        asked[n++] = bit;
        asked[n++] = bit | PELT__SHELL_WET;
    }
    asked[n++] = PELT__SHELL_GENERIC | PELT__SHELL_GPU_SKIN;
    /* The view split's face-on programs: without the read across the gap. */
    asked[n++] = PELT__SHELL_NO_GAP;
    asked[n++] = PELT__SHELL_GENERIC | PELT__SHELL_NO_GAP;
    asked[n++] = PELT__SHELL_INTER_SHADOW | PELT__SHELL_KAJIYA_KAY | PELT__SHELL_NO_GAP;
    /* The wet layers below the tufts' base: no clump lookup. */
    asked[n++] = PELT__SHELL_WET | PELT__SHELL_TUFT_BASE;
    asked[n++] = PELT__SHELL_WET | PELT__SHELL_TUFT_BASE | PELT__SHELL_RINGLETS | PELT__SHELL_KAJIYA_KAY;
    asked[n++] = PELT__SHELL_WET | PELT__SHELL_TUFT_BASE | PELT__SHELL_KAJIYA_KAY | PELT__SHELL_NO_GAP;
    asked[n++] = PELT__SHELL_GENERIC | PELT__SHELL_TUFT_BASE | PELT__SHELL_NO_GAP;
    const unsigned kept[] = {PELT__SHELL_WET, PELT__SHELL_RINGLETS, PELT__SHELL_GPU_SKIN};
    for (unsigned m = 0; m < 8; m++) {
        unsigned f = PELT__SHELL_LIGHT_PASS;
        for (unsigned k = 0; k < 3; k++)
            if (m & (1u << k)) f |= kept[k];
        asked[n++] = f;
    }
    unsigned built = 0;
    for (unsigned i = 0; i < n; i++) {
        const pelt__shell_program *sp = pelt__shell_pass_program(&pass, asked[i]);
        bool own = sp == &pass.variants[asked[i]] && sp->program != 0;
        if (!own) printf("  variant 0x%x does not build: %s\n", asked[i], logged);
        built += own;
    }
    printf("  %u of %u shell variants built\n", built, n);
    CHECK(built == n);
    CHECK(logged[0] == '\0');
    pelt__shell_pass_destroy(&pass);
    pelt__gl_state_reset();
}

/* The C images of the uniform blocks sit where GL puts the std140 members
 * (gl/uniform_blocks.c asserts the same offsets at compile time). */
static void uniform_blocks_match_their_c_structs(void)
{
    const char *vs[] = {"void main() { gl_Position = vec4(0.0); }\n", NULL};
    const char *fs[] = {"out vec4 o; void main() { o = vec4(u_ambient + u_slant); }\n", NULL};
    GLuint p = 0;
    CHECK(pelt__gl_program_create("blocks", vs, fs, &(pelt_hooks){0}, &p, NULL) == PELT_OK);
    if (!p) return;
    static const struct { const char *name; size_t offset; } members[] = {
        {"u_model", offsetof(pelt__frame_block, model)},
        {"u_view_proj", offsetof(pelt__frame_block, view_proj)},
        {"u_eye", offsetof(pelt__frame_block, eye)},
        {"u_ambient", offsetof(pelt__frame_block, ambient)},
        {"u_light_dir", offsetof(pelt__frame_block, light_dir)},
        {"u_light_color", offsetof(pelt__frame_block, light_color)},
        {"u_light_matrix", offsetof(pelt__frame_block, light_matrix)},
        {"u_shadow_map", offsetof(pelt__frame_block, shadow_map)},
        {"u_shadow_slab", offsetof(pelt__frame_block, shadow_slab)},
        {"u_color", offsetof(pelt__fur_block, color)},
        {"u_layers", offsetof(pelt__fur_block, layers)},
        {"u_tip_color", offsetof(pelt__fur_block, tip_color)},
        {"u_length", offsetof(pelt__fur_block, length)},
        {"u_specular", offsetof(pelt__fur_block, specular)},
        {"u_shininess", offsetof(pelt__fur_block, shininess)},
        {"u_fur_per_uv", offsetof(pelt__fur_block, fur_per_uv)},
        {"u_shadow", offsetof(pelt__fur_block, shadow)},
        {"u_curl_frequency", offsetof(pelt__fur_block, curl_frequency)},
        {"u_curl_radius", offsetof(pelt__fur_block, curl_radius)},
        {"u_clump_blend", offsetof(pelt__fur_block, clump_blend)},
        {"u_clump_tightness", offsetof(pelt__fur_block, clump_tightness)},
        {"u_wet_darken", offsetof(pelt__fur_block, wet_darken)},
        {"u_color_scale", offsetof(pelt__fur_block, color_scale)},
        {"u_slant", offsetof(pelt__fur_block, slant)},
        {"u_wet_gloss", offsetof(pelt__fur_block, wet_gloss)},
        {"u_wet_sharpness", offsetof(pelt__fur_block, wet_sharpness)},
        {"u_ringlets", offsetof(pelt__fur_block, ringlets)},
        {"u_wet_strays", offsetof(pelt__fur_block, wet_strays)},
        {"u_ringlet_radius", offsetof(pelt__fur_block, ringlet_radius)},
        {"u_strand_curl_radius", offsetof(pelt__fur_block, strand_curl_radius)},
        {"u_strand_curl_omega", offsetof(pelt__fur_block, strand_curl_omega)},
        {"u_strand_curl_wave", offsetof(pelt__fur_block, strand_curl_wave)},
        {"u_clump_lean", offsetof(pelt__fur_block, clump_lean)},
    };
    for (size_t i = 0; i < sizeof members / sizeof members[0]; i++) {
        GLuint index = GL_INVALID_INDEX;
        GLint offset = -1;
        glGetUniformIndices(p, 1, &members[i].name, &index);
        if (index != GL_INVALID_INDEX) glGetActiveUniformsiv(p, 1, &index, GL_UNIFORM_OFFSET, &offset);
        if (offset != (GLint)members[i].offset)
            fprintf(stderr, "  %s: GL offset %d, C offset %zu\n", members[i].name, offset,
                    members[i].offset);
        CHECK(offset == (GLint)members[i].offset);
    }
    static const struct { const char *name; size_t size; GLint binding; } blocks[] = {
        {"pelt_frame_block", sizeof(pelt__frame_block), PELT_BLOCK_FRAME},
        {"pelt_fur_block", sizeof(pelt__fur_block), PELT_BLOCK_FUR},
    };
    for (size_t i = 0; i < 2; i++) {
        GLuint index = glGetUniformBlockIndex(p, blocks[i].name);
        GLint size = 0, binding = -1;
        CHECK(index != GL_INVALID_INDEX);
        if (index == GL_INVALID_INDEX) continue;
        glGetActiveUniformBlockiv(p, index, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
        glGetActiveUniformBlockiv(p, index, GL_UNIFORM_BLOCK_BINDING, &binding);
        CHECK(size == (GLint)blocks[i].size);
        CHECK(binding == blocks[i].binding);
    }
    glDeleteProgram(p);
    pelt__gl_state_reset();
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* Distinct edges of a mesh: every triangle side once, shared or not. */
static size_t count_edges(const pelt_mesh *m)
{
    pelt_mesh_data d = pelt_mesh_get_data(m);
    uint64_t *k = malloc(d.triangle_count * 3 * sizeof *k);
    for (size_t i = 0; i < d.triangle_count * 3; i++) {
        uint64_t a = d.indices[i], b = d.indices[i % 3 == 2 ? i - 2 : i + 1];
        k[i] = a < b ? a << 32 | b : b << 32 | a;
    }
    qsort(k, d.triangle_count * 3, sizeof *k, cmp_u64);
    size_t n = 0;
    for (size_t i = 0; i < d.triangle_count * 3; i++) n += i == 0 || k[i] != k[i - 1];
    free(k);
    return n;
}

/* The stats of a draw: per-pass draw calls, layers, triangles, and the
 * bytes the frame uploaded (only what changed goes up). */
static void stats_count_passes_layers_and_uploads(void)
{
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    CHECK(pelt_fur_create(torus, &(pelt_fur_desc){.layers = 16}, &fur, NULL) == PELT_OK);
    CHECK(pelt_renderer_create(torus, fur, NULL, &r, NULL) == PELT_OK);
    if (!r) {
        pelt_fur_destroy(fur);
        return;
    }
    pelt_render_stats st = pelt_renderer_get_stats(r);
    CHECK(st.skin_draw_calls == 0 && st.shell_draw_calls == 0 && st.triangles == 0);
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(&torus_cam, (float)W / H, &v);
    const size_t tris = 9360, verts = pelt_mesh_get_data(torus).vertex_count;

    pelt_renderer_draw(r, &v, NULL);
    st = pelt_renderer_get_stats(r);
    CHECK(st.skin_draw_calls == 1 && st.shell_instances == 16);
    /* One instanced draw, or a shell at a time where the view split drew
     * the face-on triangles apart (face_on_and_side_on_drawn_apart). */
    CHECK(st.face_on_triangles > 0 && st.face_on_triangles < tris && st.shell_draw_calls == 2 * 16);
    /* Of the fins, one per edge (counted here by brute force), the ones
     * the view may show, all in one draw; the full torus, every shell. */
    CHECK(st.fin_draw_calls == 1 && st.fins > 0 && st.fins < count_edges(torus));
    CHECK(st.mesh_level == 0 && st.mesh_triangles == tris && st.shell_level == 0 && st.culled);
    CHECK(st.triangles == tris * 17 + st.fins * 2 * PELT_FIN_ROWS + st.outline_hairs * 2 * st.fin_rows);
    /* Nothing changed since create: the frame block and this view's fins
     * (16 bytes a fin, and their vertices), the fins alone when drawn. */
    CHECK(st.upload_bytes > sizeof(pelt__frame_block) + st.fins * 16);
    pelt_renderer_draw(r, &v, &(pelt_draw_desc){.no_fins = true});
    st = pelt_renderer_get_stats(r);
    CHECK(st.upload_bytes == sizeof(pelt__frame_block));

    pelt_fur_step(fur, 1.0f / 60.0f, &(pelt_forces){0});
    pelt_fur_add_droplet(fur, &(pelt_droplet){{0.5f, 0.5f}, 0.05f, 1.0f}, NULL);
    pelt_renderer_upload(r); /* counted with the next draw */
    pelt_renderer_draw(r, &v, &(pelt_draw_desc){.no_fins = true, .first_layer = 4, .layer_count = 3});
    st = pelt_renderer_get_stats(r);
    CHECK(st.shell_instances == 3 && st.triangles == tris * 4);
    printf("  upload after a step and a droplet: %zu bytes\n", st.upload_bytes);
    CHECK(st.upload_bytes > sizeof(pelt__frame_block) + verts * 3 * sizeof(float));

    pelt_renderer_draw(r, &v, &(pelt_draw_desc){.no_skin = true, .no_fins = true, .first_layer = 16});
    st = pelt_renderer_get_stats(r);
    CHECK(st.skin_draw_calls == 0 && st.shell_draw_calls == 0 && st.triangles == 0);
    pelt_renderer_draw(r, &v, &(pelt_draw_desc){.debug.no_shells = true, .no_fins = true});
    st = pelt_renderer_get_stats(r);
    CHECK(st.skin_draw_calls == 1 && st.shell_draw_calls == 0 && st.triangles == tris);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
}

/* Checks GL state against the contract of pelt/render.h. */
static void check_state_contract(const char *after)
{
    GLint v;
#define EXPECT_GL(pname, want)                                                           \
    do {                                                                                 \
        glGetIntegerv(pname, &v);                                                        \
        if (v != (GLint)(want))                                                          \
            fprintf(stderr, "  after %s: %s = 0x%x, want 0x%x\n", after, #pname, (unsigned)v, \
                    (unsigned)(want));                                                   \
        CHECK(v == (GLint)(want));                                                       \
    } while (0)
    EXPECT_GL(GL_CURRENT_PROGRAM, 0);
    EXPECT_GL(GL_VERTEX_ARRAY_BINDING, 0);
    EXPECT_GL(GL_ARRAY_BUFFER_BINDING, 0);
    EXPECT_GL(GL_UNIFORM_BUFFER_BINDING, 0);
    for (GLuint i = 0; i < PELT_BLOCK_COUNT; i++) {
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, i, &v);
        CHECK(v == 0);
    }
    EXPECT_GL(GL_ACTIVE_TEXTURE, GL_TEXTURE0);
    for (GLenum u = 0; u < PELT_UNIT_COUNT; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        EXPECT_GL(GL_TEXTURE_BINDING_2D, 0);
        EXPECT_GL(GL_TEXTURE_BINDING_2D_ARRAY, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    CHECK(!glIsEnabled(GL_DEPTH_TEST));
    EXPECT_GL(GL_DEPTH_FUNC, GL_LESS);
    EXPECT_GL(GL_DEPTH_WRITEMASK, GL_TRUE);
    CHECK(!glIsEnabled(GL_BLEND));
    EXPECT_GL(GL_BLEND_SRC_RGB, GL_ONE);
    EXPECT_GL(GL_BLEND_SRC_ALPHA, GL_ONE);
    EXPECT_GL(GL_BLEND_DST_RGB, GL_ZERO);
    EXPECT_GL(GL_BLEND_DST_ALPHA, GL_ZERO);
    EXPECT_GL(GL_BLEND_EQUATION_RGB, GL_FUNC_ADD);
    EXPECT_GL(GL_BLEND_EQUATION_ALPHA, GL_FUNC_ADD);
    CHECK(!glIsEnabled(GL_CULL_FACE));
    EXPECT_GL(GL_PIXEL_UNPACK_BUFFER_BINDING, 0);
    EXPECT_GL(GL_UNPACK_ALIGNMENT, 4);
    EXPECT_GL(GL_UNPACK_ROW_LENGTH, 0);
    EXPECT_GL(GL_UNPACK_SKIP_ROWS, 0);
    EXPECT_GL(GL_UNPACK_SKIP_PIXELS, 0);
    EXPECT_GL(GL_UNPACK_IMAGE_HEIGHT, 0);
    EXPECT_GL(GL_UNPACK_SKIP_IMAGES, 0);
#undef EXPECT_GL
    CHECK(glGetError() == GL_NO_ERROR);
}

/* A caller's render loop leaves all kinds of state behind. Objects the
 * caller owns: a texture, a buffer, a vertex array. */
typedef struct caller_objects {
    GLuint texture, buffer, vao;
} caller_objects;

static void mess_up_state(const caller_objects *o)
{
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_COLOR);
    glBindTexture(GL_TEXTURE_2D, o->texture);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_COUNT + 2); /* a unit pelt leaves alone */
    glBindTexture(GL_TEXTURE_2D, o->texture);
    glBindVertexArray(o->vao);
    glBindBuffer(GL_ARRAY_BUFFER, o->buffer);
    glBindBufferBase(GL_UNIFORM_BUFFER, PELT_BLOCK_FUR, o->buffer);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, o->buffer);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 3);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 2);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 5);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 1);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT_AND_BACK);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_ONE);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_NEVER);
    glDepthMask(GL_FALSE);
}

/* Wet, spotted fur on the square: every upload path (volume, colour
 * texture, mask rectangle, tips) has something to send. */
static uint8_t *render_with_state(bool messy, const caller_objects *o)
{
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    uint8_t *px = malloc((size_t)W * H * 4);
    const pelt_camera cam = {0.0f, 35.0f, 2.6f, 45.0f, {0, 0, 0}};
    CHECK(pelt_fur_create(square, &(pelt_fur_desc){.look.texture_size = 64}, &fur, NULL) == PELT_OK);
    pelt_headless_bind(gl);
    if (messy) mess_up_state(o);
    CHECK(pelt_renderer_create(square, fur, NULL, &r, NULL) == PELT_OK);
    if (messy) check_state_contract("create");
    CHECK(pelt_fur_set_color_pattern(fur, PELT_COLOR_PATTERN_SPOTS, 3, NULL) == PELT_OK);
    wet_left_half(fur, NULL);
    if (messy) mess_up_state(o);
    pelt_renderer_upload(r);
    if (messy) check_state_contract("upload");
    pelt_fur_step(fur, 1.0f / 60.0f, &(pelt_forces){.wind = {5.0f, 0.0f, 0.0f}});
    pelt_fur_add_droplet(fur, &(pelt_droplet){{0.8f, 0.3f}, 0.1f, 1.0f}, NULL);
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(&cam, (float)W / H, &v);
    v.light = (pelt_light){{0.5f, 1.0f, 0.8f}, {1.5f, 1.45f, 1.4f}, 0.25f};
    glDepthMask(GL_TRUE);
    glClearColor(gl_test_background[0], gl_test_background[1], gl_test_background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (messy) mess_up_state(o);
    GLint fb_before = 0, vp_before[4], vp_after[4], fb_after = -1, unit_after = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb_before);
    glGetIntegerv(GL_VIEWPORT, vp_before);
    pelt_renderer_draw(r, &v, NULL);
    if (messy) {
        check_state_contract("draw");
        /* What the contract says pelt does not touch, it did not touch. */
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb_after);
        glGetIntegerv(GL_VIEWPORT, vp_after);
        glActiveTexture(GL_TEXTURE0 + PELT_UNIT_COUNT + 2);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit_after);
        glActiveTexture(GL_TEXTURE0);
        CHECK(fb_after == fb_before);
        CHECK(!memcmp(vp_after, vp_before, sizeof vp_after));
        CHECK(unit_after == (GLint)o->texture);
        glCullFace(GL_BACK);
    }
    if (px) pelt_headless_read_rgba8(gl, px);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
    return px;
}

/* pelt/render.h's GL state contract: whatever state the caller left, each
 * call sets what it needs (the picture is the same bit for bit) and leaves
 * GL's initial values behind for everything it touches. */
static void calls_leave_gl_state_as_render_h_states(void)
{
    caller_objects o;
    glGenTextures(1, &o.texture);
    glBindTexture(GL_TEXTURE_2D, o.texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenBuffers(1, &o.buffer);
    glBindBuffer(GL_ARRAY_BUFFER, o.buffer);
    glBufferData(GL_ARRAY_BUFFER, 256, NULL, GL_STATIC_DRAW);
    glGenVertexArrays(1, &o.vao);
    pelt__gl_state_reset();
    uint8_t *clean = render_with_state(false, &o);
    uint8_t *messy = render_with_state(true, &o);
    CHECK(clean && messy);
    if (clean && messy) {
        size_t differ = 0;
        for (size_t i = 0; i < (size_t)W * H * 4; i++) differ += clean[i] != messy[i];
        printf("  %zu bytes differ between the clean and the messy start\n", differ);
        CHECK(differ == 0);
        CHECK(gl_test_coverage(clean, (size_t)W * H) > (size_t)W * H / 4);
    }
    free(clean);
    free(messy);
    glDeleteTextures(1, &o.texture);
    glDeleteBuffers(1, &o.buffer);
    glDeleteVertexArrays(1, &o.vao);
    pelt__gl_state_reset();
}

int main(void)
{
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    if (gl_test_meshes(&torus, &square)) {
        RUN(golden_torus_default_fur);
        RUN(golden_square_default_fur);
        RUN(fur_covers_beyond_bare_silhouette);
        RUN(longer_fur_covers_more);
        RUN(shells_are_one_instanced_draw);
        RUN(plain_renderer_draws_every_shell);
        RUN(wet_and_dry_drawn_apart);
        RUN(wet_and_dry_each_drawn_apart_by_the_view);
        RUN(wet_fur_drawn_as_dry_is_the_towelled_picture);
        RUN(wet_layers_below_the_tufts_base_drawn_lean);
        RUN(face_on_and_side_on_drawn_apart);
        RUN(wet_and_dry_drawn_apart_at_a_grazing_angle);
        RUN(sub_shells_join_a_tufts_hairs);
        RUN(wet_clumps_show_skin_and_leave_dry_fur_alone);
        RUN(dried_fur_matches_dry_render);
        RUN(clumps_grow_thinner_toward_the_tips);
        RUN(wet_fur_highlight_peak_rises_with_wetness);
        RUN(soaked_ringlets_render_as_straight_fur);
        RUN(soaked_square_makes_tufts_by_clump_size);
        RUN(tufts_keep_their_roots_and_gather_at_the_tips);
        RUN(drying_loosens_the_tufts_step_by_step);
        RUN(tuft_highlight_rises_with_wetness);
        RUN(wet_skin_sheen_rises_with_wetness);
        RUN(renderer_allocates_through_its_hooks);
        RUN(renderer_creation_survives_each_failed_allocation);
        RUN(program_errors_reach_the_logger);
        RUN(strand_reference_failure_is_reported);
        RUN(every_shell_variant_compiles);
        RUN(uniform_blocks_match_their_c_structs);
        RUN(stats_count_passes_layers_and_uploads);
        RUN(calls_leave_gl_state_as_render_h_states);
    }
    pelt_mesh_destroy(torus);
    pelt_mesh_destroy(square);
    pelt_headless_destroy(gl);
    return check_summary();
}
