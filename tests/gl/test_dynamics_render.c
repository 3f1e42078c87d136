/* Images of dynamic fur on Mesa llvmpipe: wind leans the fur of
 * Silva et al. Fig. 4b downwind, shells stay joined under strong wind, a
 * turntable leaves the tips behind, and the four curl looks of Fig. 7
 * differ. Properties only: no reference images. */
#include "support/gl_test.h"

#include "core/fur/fur_internal.h"
#include "core/mesh/mesh_internal.h"

#include <math.h>

enum { W = 160, H = 120 };
#define NPX ((size_t)W * H)
#define DT (1.0f / 60.0f)

static pelt_headless *gl;
static pelt_mesh *torus, *square;
static const pelt_camera torus_cam = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
static const pelt_camera curl_cam = {30.0f, 20.0f, 3.2f, 40.0f, {0, 0, 0}};
/* Looking down at the square from above, from the +Z side: image right is
 * world +X, so fur leaning +X spills past the right edge. */
static const pelt_camera above_cam = {0.0f, 75.0f, 3.6f, 40.0f, {0, 0, 0}};

/* What a tweak does to the fur before it is drawn: `seconds` of steps at
 * 1/60 s under `forces`, spinning the mesh about +Y at `spin` deg/s. */
typedef struct motion {
    pelt_forces forces;
    float seconds;
    float spin;
} motion;

static void rotation_y(float deg, float m[16])
{
    float a = deg * 3.14159265f / 180.0f, c = cosf(a), s = sinf(a);
    memset(m, 0, 16 * sizeof *m);
    m[0] = c;
    m[2] = -s;
    m[5] = 1.0f;
    m[8] = s;
    m[10] = c;
    m[15] = 1.0f;
}

static void run_motion(pelt_fur *fur, void *user)
{
    const motion *mo = user;
    int frames = (int)(mo->seconds / DT + 0.5f);
    for (int i = 1; i <= frames; i++) {
        if (mo->spin != 0.0f) {
            float m[16];
            rotation_y(mo->spin * DT * (float)i, m);
            CHECK(pelt_fur_set_transform(fur, m, NULL) == PELT_OK);
        }
        pelt_fur_step(fur, DT, &mo->forces);
    }
}

/* Keeps an image in the build dir for a person to look at. */
static void save(const char *name, const uint8_t *px)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.png", PELT_TEST_OUT, name);
    if (px) stbi_write_png(path, W, H, 4, px, W * 4);
}

static bool is_covered(const uint8_t *px, size_t i) { return gl_test_coverage(px + 4 * i, 1) == 1; }

static double mean_abs_diff(const uint8_t *a, const uint8_t *b)
{
    double sum = 0.0;
    for (size_t i = 0; i < NPX; i++)
        for (int k = 0; k < 3; k++) sum += abs((int)a[4 * i + k] - (int)b[4 * i + k]);
    return sum / (3.0 * (double)NPX);
}

/* Covered pixels left of column x0 and right of column x1, and the mean
 * column of all covered pixels. */
static void side_counts(const uint8_t *px, int x0, int x1, size_t *left, size_t *right, double *cx)
{
    double sum = 0.0;
    size_t n = 0;
    *left = *right = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (!is_covered(px, (size_t)y * W + (size_t)x)) continue;
            sum += x;
            n++;
            if (x < x0) (*left)++;
            if (x > x1) (*right)++;
        }
    *cx = n ? sum / (double)n : 0.0;
}

static pelt_forces no_gravity(void)
{
    pelt_forces f = pelt_forces_default();
    f.gravity[1] = 0.0f;
    return f;
}

/* Silva Fig. 4b: a steady wind along +X moves the fur's silhouette past
 * the square's +X edge, not past its -X edge. */
static void wind_leans_fur_downwind(void)
{
    pelt_view v;
    pelt_camera_to_view(&above_cam, (float)W / H, &v);
    CHECK(v.view[0] > 0.9f); /* world +X is image right */

    /* dense fur so the silhouette is solid, not a few scattered hairs */
    pelt_fur_desc d = {.length = 0.2f, .layers = 24, .look.texture_size = 128, .look.density = 4000.0f,
                       .look.strand_radius = 2.5f};
    pelt_draw_desc bare = {.debug.no_shells = true, .no_fins = true};
    motion calm = {no_gravity(), 1.5f, 0.0f}, windy = calm;
    windy.forces.wind[0] = 20.0f;
    windy.forces.gust_strength = 0.3f;
    uint8_t *skin = gl_test_render(gl, square, &d, &above_cam, &bare, NULL, NULL);
    uint8_t *a = gl_test_render(gl, square, &d, &above_cam, NULL, run_motion, &calm);
    uint8_t *b = gl_test_render(gl, square, &d, &above_cam, NULL, run_motion, &windy);
    CHECK(skin && a && b);
    if (skin && a && b) {
        int x0 = W, x1 = -1;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                if (is_covered(skin, (size_t)y * W + (size_t)x)) {
                    if (x < x0) x0 = x;
                    if (x > x1) x1 = x;
                }
        CHECK(x0 < x1);
        size_t la, ra, lb, rb;
        double ca, cb;
        side_counts(a, x0, x1, &la, &ra, &ca);
        side_counts(b, x0, x1, &lb, &rb, &cb);
        save("dyn_wind_calm", a);
        save("dyn_wind_plusx", b);
        printf("  square spans columns %d..%d\n", x0, x1);
        printf("  windless: %zu px beyond -X edge, %zu beyond +X edge, centroid x %.2f\n", la, ra, ca);
        printf("  wind +X : %zu px beyond -X edge, %zu beyond +X edge, centroid x %.2f\n", lb, rb, cb);
        CHECK(rb > ra + 20);
        CHECK(rb > 3 * lb + 20);
        CHECK(lb <= la);
        CHECK(cb > ca + 1.0);
    }
    free(skin);
    free(a);
    free(b);
}

/* Background pixels of a shells-only image inside the bare skin's
 * silhouette eroded by `erode` pixels: light coming through the fur where
 * adjacent triangles' shells have parted. */
static size_t background_inside_skin(const uint8_t *skin, const uint8_t *shells, int erode, size_t *inside)
{
    size_t holes = 0;
    *inside = 0;
    for (int y = erode; y < H - erode; y++)
        for (int x = erode; x < W - erode; x++) {
            bool in = true;
            for (int dy = -erode; dy <= erode && in; dy++)
                for (int dx = -erode; dx <= erode && in; dx++)
                    in = is_covered(skin, (size_t)(y + dy) * W + (size_t)(x + dx));
            if (!in) continue;
            (*inside)++;
            if (!is_covered(shells, (size_t)y * W + (size_t)x)) holes++;
        }
    return holes;
}

/* Nearly opaque fur: every shell covers its triangle, so a background
 * pixel inside the skin can only be a crack between triangles. */
static const pelt_fur_desc opaque_fur = {
    .look.texture_size = 128, .look.density = 15000.0f, .look.strand_radius = 4.0f, .look.taper = 1e-6f};

static size_t crack_pixels(const pelt_mesh *mesh, const pelt_fur_desc *d, const pelt_camera *cam,
                           motion *mo, const char *what)
{
    pelt_draw_desc bare = {.debug.no_shells = true, .no_fins = true}, shells = {.no_skin = true};
    uint8_t *skin = gl_test_render(gl, mesh, d, cam, &bare, NULL, NULL);
    uint8_t *fur = gl_test_render(gl, mesh, d, cam, &shells, run_motion, mo);
    size_t holes = (size_t)-1, inside = 0;
    CHECK(skin && fur);
    if (skin && fur) {
        holes = background_inside_skin(skin, fur, 2, &inside);
        printf("  %s: %zu background px of %zu inside the eroded skin\n", what, holes, inside);
        CHECK(inside > NPX / 20);
    }
    free(skin);
    free(fur);
    return holes;
}

static motion gale(void)
{
    motion mo = {pelt_forces_default(), 1.0f, 0.0f};
    mo.forces.wind[0] = 60.0f;
    mo.forces.wind[2] = 25.0f;
    mo.forces.gust_strength = 1.0f;
    mo.forces.gust_scale = 0.3f;
    return mo;
}

/* A roof over the XZ plane: ridge along Z at x = 0, slopes of 0.6, built
 * from a grid of n x n quads. With `split` the ridge vertices are doubled,
 * each copy with its own slope's normal (a strand per triangle side, as
 * Silva et al. have one per triangle); otherwise they are shared and the
 * normal is the average. Freed by the caller. */
static pelt_mesh *roof(unsigned n, bool split)
{
    unsigned cols = n + 1 + (split ? 1u : 0u), rows = n + 1;
    size_t vc = (size_t)cols * rows;
    float *pos = calloc(vc * 3, sizeof *pos), *nrm = calloc(vc * 3, sizeof *nrm);
    uint32_t *idx = calloc((size_t)n * n * 6, sizeof *idx);
    pelt_mesh *m = NULL;
    if (pos && nrm && idx) {
        const float slope = 0.6f, inv = 1.0f / sqrtf(1.0f + slope * slope);
        for (unsigned r = 0; r < rows; r++)
            for (unsigned c = 0; c < cols; c++) {
                /* grid column of this vertex; with split the ridge column repeats */
                unsigned g = (split && c > n / 2) ? c - 1 : c;
                float x = -1.0f + 2.0f * (float)g / (float)n, z = -1.0f + 2.0f * (float)r / (float)n;
                float *p = pos + 3 * ((size_t)r * cols + c), *q = nrm + 3 * ((size_t)r * cols + c);
                bool left = split ? c <= n / 2 : g < n / 2;
                bool ridge = !split && g == n / 2;
                p[0] = x;
                p[1] = slope * (1.0f - fabsf(x));
                p[2] = z;
                q[0] = ridge ? 0.0f : (left ? -slope : slope) * inv;
                q[1] = ridge ? 1.0f : inv;
                q[2] = 0.0f;
            }
        size_t t = 0;
        for (unsigned r = 0; r < n; r++)
            for (unsigned g = 0; g < n; g++) {
                unsigned c = (split && g >= n / 2) ? g + 1 : g;
                uint32_t a = r * cols + c, b = a + 1, e = a + cols, f = e + 1;
                uint32_t tri[6] = {a, e, b, b, e, f};
                memcpy(idx + 6 * t++, tri, sizeof tri);
            }
        pelt_mesh_data md = {pos, nrm, NULL, vc, idx, (size_t)n * n * 2};
        pelt_error err = {0};
        if (pelt_mesh_create(&md, &m, &err) != PELT_OK) fprintf(stderr, "  roof: %s\n", err.message);
    }
    free(pos);
    free(nrm);
    free(idx);
    return m;
}

/* docs/dynamics.md: one strand per vertex keeps adjacent shells joined. Under a
 * gale with gusts the closed torus shows no background through its shells;
 * the counter does see the cracks of a creased surface whose strands are
 * split along the crease, and none when they are shared. */
static void no_cracks_under_strong_wind(void)
{
    pelt_fur_desc d = opaque_fur;
    motion mo = gale();
    size_t torus_holes = crack_pixels(torus, &d, &torus_cam, &mo, "torus, gale, shells and fins");
    CHECK(torus_holes == 0);

    /* The control: seen from above, nothing lies behind a crack in the
     * roof. Few layers so the lowest layer's crack is wider than a pixel. */
    static const pelt_camera above = {0.0f, 80.0f, 3.2f, 40.0f, {0, 0, 0}};
    pelt_fur_desc dr = opaque_fur;
    dr.layers = 4;
    dr.length = 0.2f;
    motion still = {no_gravity(), 0.0f, 0.0f};
    pelt_mesh *shared = roof(16, false), *split = roof(16, true);
    CHECK(shared && split);
    if (shared && split) {
        size_t s0 = crack_pixels(shared, &dr, &above, &still, "roof, shared ridge, at rest");
        size_t s1 = crack_pixels(shared, &dr, &above, &mo, "roof, shared ridge, gale");
        size_t c0 = crack_pixels(split, &dr, &above, &still, "roof, split ridge, at rest");
        CHECK(s0 == 0);
        CHECK(s1 == 0);
        CHECK(c0 > 20 && c0 != (size_t)-1);
    }
    pelt_mesh_destroy(shared);
    pelt_mesh_destroy(split);
}

/* Spinning the torus about +Y: in world space the tips trail behind their
 * roots' motion (drag against still air, strand.h), and the picture
 * differs from the still one. */
static void turntable_fur_lags_behind_motion(void)
{
    const float spin = 180.0f; /* deg/s */
    pelt_fur_desc d = {0};
    pelt_fur *fur = NULL;
    CHECK(pelt_fur_create(torus, &d, &fur, NULL) == PELT_OK);
    if (!fur) return;
    motion mo = {no_gravity(), 0.5f, spin};
    run_motion(fur, &mo);
    float m[16], L0 = pelt_fur_get_desc(fur).length;
    rotation_y(spin * 0.5f, m);
    const float w = spin * 3.14159265f / 180.0f;
    double sum = 0.0, sum_lag = 0.0;
    size_t behind = 0, n = torus->vertex_count;
    for (size_t i = 0; i < n; i++) {
        float root[3], tip[3];
        pelt__strands_root_world(fur->strands, i, root);
        pelt__strands_tip_world(fur->strands, i, tip);
        const float *nl = torus->normals + 3 * i;
        /* rest tip root + L0 R n, and the root's velocity w (0,1,0) x root */
        float nw[3] = {m[0] * nl[0] + m[8] * nl[2], nl[1], m[2] * nl[0] + m[10] * nl[2]};
        float vel[3] = {w * root[2], 0.0f, -w * root[0]};
        float dot = 0.0f, speed = sqrtf(vel[0] * vel[0] + vel[2] * vel[2]);
        for (int k = 0; k < 3; k++) dot += (tip[k] - root[k] - L0 * nw[k]) * vel[k];
        sum += dot;
        if (speed > 0.0f) sum_lag += dot / speed;
        if (dot < 0.0f) behind++;
    }
    double mean_lag = sum_lag / (double)n;
    printf("  after 0.5 s at %.0f deg/s: mean dot(tip - rest tip, v_root) %.4f, mean lag along the "
           "motion %.4f (L0 %.3f), %zu of %zu tips behind\n",
           spin, sum / (double)n, mean_lag, L0, behind, n);
    CHECK(sum < 0.0);
    CHECK(mean_lag < -0.05 * L0);
    CHECK(behind > n * 9 / 10);
    pelt_fur_destroy(fur);

    motion still = {no_gravity(), 0.5f, 0.0f};
    uint8_t *a = gl_test_render(gl, torus, &d, &torus_cam, NULL, run_motion, &still);
    uint8_t *b = gl_test_render(gl, torus, &d, &torus_cam, NULL, run_motion, &mo);
    CHECK(a && b);
    if (a && b) {
        double diff = mean_abs_diff(a, b);
        printf("  image still vs spinning (mesh-local view): mean abs diff %.3f\n", diff);
        CHECK(diff > 1.0);
    }
    free(a);
    free(b);
}

/* Silva Fig. 7: straight, wavy, few large curls, many small curls. */
static void curl_presets_differ(void)
{
    static const char *names[4] = {"straight", "wavy", "few-large-curls", "many-small-curls"};
    uint8_t *img[4] = {0};
    for (int i = 0; i < 4; i++) {
        pelt_fur_desc d = {.layers = 32, .length = 0.15f};
        pelt_error err = {0};
        CHECK(pelt_fur_desc_curl_preset(&d, torus, names[i], &err) == PELT_OK);
        printf("  %-16s omega %.3f K %.4f\n", names[i], (double)d.look.curl_frequency, (double)d.look.curl_radius);
        img[i] = gl_test_render(gl, torus, &d, &curl_cam, NULL, NULL, NULL);
        CHECK(img[i] != NULL);
    }
    printf("  mean abs diff (0..255):\n");
    for (int i = 0; i < 4; i++) {
        printf("  %-16s", names[i]);
        for (int j = 0; j < 4; j++) {
            double e = (img[i] && img[j]) ? mean_abs_diff(img[i], img[j]) : -1.0;
            printf(" %7.3f", e);
            if (i < j) CHECK(e > 1.0);
            if (i == j) CHECK(e == 0.0);
        }
        printf("\n");
    }
    for (int i = 0; i < 4; i++) free(img[i]);
}

/* How far the fur's luminance stays alike along the rows of a w-wide
 * picture: the sum over lags of 1..LAGS pixels of the rows' normalised
 * autocorrelation where it is positive, over rows y0..y1 and the middle
 * 5/6 of the width. Seen from the side, a lock of curls lies over in a
 * swirl and lengthens it. */
static double row_correlation_length(const uint8_t *px, int w, int y0, int y1)
{
    enum { LAGS = 32 };
    const int x0 = w / 12, x1 = w - w / 12, cw = x1 - x0, ch = y1 - y0;
    double *l = malloc((size_t)cw * (size_t)ch * sizeof *l);
    if (!l) return 0.0;
    double mean = 0.0, var = 0.0;
    const size_t n = (size_t)cw * (size_t)ch;
    for (int y = 0; y < ch; y++)
        for (int x = 0; x < cw; x++) {
            double v = gl_test_luma(px + ((size_t)(y0 + y) * (size_t)w + (size_t)(x0 + x)) * 4);
            l[(size_t)y * (size_t)cw + (size_t)x] = v;
            mean += v;
        }
    mean /= (double)n;
    for (size_t i = 0; i < n; i++) var += (l[i] - mean) * (l[i] - mean);
    var /= (double)n;
    double sum = 0.0;
    for (int lag = 1; lag <= LAGS && var > 0.0; lag++) {
        double c = 0.0;
        size_t k = 0;
        for (int y = 0; y < ch; y++)
            for (int x = 0; x + lag < cw; x++, k++) {
                const double *row = l + (size_t)y * (size_t)cw;
                c += (row[x] - mean) * (row[x + lag] - mean);
            }
        c /= (double)k * var;
        if (c > 0.0) sum += c;
    }
    free(l);
    return sum;
}

/* Curly hair gathers in locks whose size follows the curl's
 * (docs/method.md, Ringlets): seen from the side as in Silva Fig. 7's
 * gallery (docs/gallery-papers.md: 480 x 360, 12 degrees above a square
 * of long sparse fur), a few large curls lie over in swirls that stretch
 * the rows' features further than many small curls do, and further than
 * the same curls with every strand its own phase (no locks). */
static void curl_locks_follow_the_curls_scale(void)
{
    enum { BW = 480, BH = 360 };
    static const char *names[2] = {"few-large-curls", "many-small-curls"};
    const pelt_camera side = {0.0f, 12.0f, 2.2f, 40.0f, {0, 0, 0}};
    pelt_headless *big = gl_test_open(BW, BH, false);
    CHECK(big != NULL);
    if (!big) return;
    double len[2][2] = {{0}};
    for (int phase = 0; phase < 2; phase++)
        for (int i = 0; i < 2; i++) {
            pelt_fur_desc d = {.layers = 48, .length = 0.3f};
            d.look.density = 500.0f, d.look.strand_radius = 2.5f, d.look.taper = 0.3f;
            d.look.curl_phase = phase == 0 ? PELT_CURL_RINGLETS : PELT_CURL_STRANDS;
            pelt_error err = {0};
            CHECK(pelt_fur_desc_curl_preset(&d, square, names[i], &err) == PELT_OK);
            uint8_t *img = gl_test_render(big, square, &d, &side, NULL, NULL, NULL);
            CHECK(img != NULL);
            /* The fur's top face, above its front edge's columns of hair
             * (which start near row 200). */
            if (img) len[phase][i] = row_correlation_length(img, BW, 140, 200);
            if (img) {
                char path[1024];
                snprintf(path, sizeof path, "%s/curl_%s_%s.png", PELT_TEST_OUT, phase == 0 ? "locks" : "strands",
                         names[i]);
                stbi_write_png(path, BW, BH, 4, img, BW * 4);
            }
            free(img);
        }
    pelt_headless_destroy(big);
    printf("  the rows' correlation length (px): in locks few large %.2f, many small %.2f; every strand its "
           "own phase few large %.2f, many small %.2f\n",
           len[0][0], len[0][1], len[1][0], len[1][1]);
    CHECK(len[0][0] > 1.4 * len[0][1]); /* the presets differ by the curls' scale */
    CHECK(len[0][0] > 1.4 * len[1][0]); /* the locks make it */
}

int main(void)
{
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    if (gl_test_meshes(&torus, &square)) {
        RUN(wind_leans_fur_downwind);
        RUN(no_cracks_under_strong_wind);
        RUN(turntable_fur_lags_behind_motion);
        RUN(curl_presets_differ);
        RUN(curl_locks_follow_the_curls_scale);
    }
    pelt_mesh_destroy(torus);
    pelt_mesh_destroy(square);
    pelt_headless_destroy(gl);
    return check_summary();
}
