/* The default camera frames any mesh (pelt_camera_frame through the scene
 * runner): every mesh of Debian's libcgal-demo data archive that
 * loads is rendered as `pelt render --mesh FILE` would, without camera keys,
 * small and with few layers. No hair may touch the picture's border (the
 * fur would be cut there), and on the creatures the fur covers between 15%
 * and 60% of the picture: the whole animal, large enough to see. */
#define _POSIX_C_SOURCE 200809L /* opendir, stat */
#include "support/corpus.h"
#include "support/gl_test.h"

#include "pelt/scene_instance.h"

#define CORPUS_DIR PELT_TEST_OUT "/framing_corpus"
enum { W = 160, H = 120 };

/* Animals and figures of the archive: the meshes a user frames to show a
 * furry creature. */
static const char *const creatures[] = {
    "armadillo.off", "bear.off",   "bear_bis.off",   "bull.off",     "bunny00.off",
    "camel.off",     "cow.off",    "ChineseDragon-10kv.off", "diplodocus.off", "dino.off",
    "elephant.off",  "elephant-with-holes.off", "elk.off", "homer.off", "lion.off", "man.off",
    "mannequin-devil.off", "pig.off", "pig.stl", "refined_elephant.off", "triceratops.off",
};

static bool is_creature(const char *name)
{
    for (size_t i = 0; i < sizeof creatures / sizeof creatures[0]; i++)
        if (strcmp(creatures[i], name) == 0) return true;
    return false;
}

static bool background(const uint8_t *p)
{
    for (int k = 0; k < 3; k++) {
        int b = (int)(gl_test_background[k] * 255.0f + 0.5f);
        if (abs((int)p[k] - b) > 6) return false;
    }
    return true;
}

typedef struct framed {
    double coverage;   /* share of pixels that are not background */
    size_t border;     /* of them, pixels on the outermost rows and columns */
} framed;

/* Renders the mesh file as `pelt render --mesh` does (the scene's defaults,
 * no camera key) at W x H with 4 layers. False when it does not load. */
static bool render_framed(pelt_headless *gl, const char *path, framed *out, const char *dump)
{
    pelt_scene sc;
    pelt_scene_defaults(&sc);
    pelt_error err = {0};
    if (pelt_scene_set(&sc, "mesh.file", path, &err) != PELT_OK) return false;
    sc.output.width = W, sc.output.height = H;
    sc.fur.layers = 4;
    sc.atlas.mode = PELT_ATLAS_MESH_UVS; /* framing needs no patches: faster */
    memcpy(sc.output.background, gl_test_background, sizeof gl_test_background);
    pelt_scene_instance_desc idesc = {.cache_dir = ""};
    pelt_scene_instance *inst = NULL;
    pelt_renderer *r = NULL;
    bool ok = pelt_scene_instantiate(&sc, &idesc, &inst, &err) == PELT_OK;
    pelt_scene_free(&sc);
    if (!ok) return false;
    if (pelt_renderer_create(pelt_scene_instance_mesh(inst), pelt_scene_instance_fur(inst), NULL, &r,
                             &err) != PELT_OK) {
        fprintf(stderr, "  %s: renderer: %s\n", path, err.message);
        CHECK(false);
        pelt_scene_instance_destroy(inst);
        return false;
    }
    static uint8_t px[W * H * 4];
    pelt_headless_bind(gl);
    glClearColor(gl_test_background[0], gl_test_background[1], gl_test_background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_view view = pelt_scene_instance_view(inst);
    pelt_renderer_draw(r, &view, NULL);
    pelt_headless_read_rgba8(gl, px);
    if (dump) stbi_write_png(dump, W, H, 4, px, W * 4);
    size_t covered = 0, border = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (background(px + 4 * (y * W + x))) continue;
            covered++;
            if (x == 0 || y == 0 || x == W - 1 || y == H - 1) border++;
        }
    out->coverage = (double)covered / (double)(W * H);
    out->border = border;
    pelt_renderer_destroy(r);
    pelt_scene_instance_destroy(inst);
    return true;
}

static pelt_headless *gl;

static void cgal_meshes_are_framed_whole(void)
{
    char *names[1024];
    long listed = corpus_list(CORPUS_DIR, names, 1024);
    CHECK(listed >= 0);
    if (listed < 0) return;
    size_t rendered = 0, creatures_seen = 0;
    double lo = 1.0, hi = 0.0;
    printf("  %-28s %9s %7s\n", "mesh", "coverage", "border");
    for (long i = 0; i < listed; i++) {
        char path[2048], dump[2048];
        snprintf(path, sizeof path, "%s/data/meshes/%s", CORPUS_DIR, names[i]);
        snprintf(dump, sizeof dump, "%s/framed_%s.png", CORPUS_DIR, names[i]);
        framed f;
        if (!render_framed(gl, path, &f, dump)) { /* not a mesh pelt loads */
            free(names[i]);
            continue;
        }
        rendered++;
        bool creature = is_creature(names[i]);
        printf("  %-28s %8.1f%% %7zu%s\n", names[i], 100.0 * f.coverage, f.border,
               creature ? "  creature" : "");
        if (f.border) fprintf(stderr, "  %s: %zu fur pixels on the border (%s)\n", names[i], f.border, dump);
        CHECK(f.border == 0);
        CHECK(f.coverage > 0.0);
        if (creature) {
            creatures_seen++;
            if (f.coverage < lo) lo = f.coverage;
            if (f.coverage > hi) hi = f.coverage;
            if (!(f.coverage >= 0.15 && f.coverage <= 0.60))
                fprintf(stderr, "  %s: coverage %.1f%% outside 15..60%% (%s)\n", names[i],
                        100.0 * f.coverage, dump);
            CHECK(f.coverage >= 0.15 && f.coverage <= 0.60);
        }
        free(names[i]);
    }
    printf("  %zu meshes framed, %zu creatures covering %.1f%% .. %.1f%%\n", rendered, creatures_seen,
           100.0 * lo, 100.0 * hi);
    CHECK(rendered > 0);
    CHECK(creatures_seen == sizeof creatures / sizeof creatures[0]);
}

int main(void)
{
    if (!corpus_available())
        return check_skip("libcgal-demo is not installed (" CGAL_ARCHIVE " is missing)");
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    RUN(cgal_meshes_are_framed_whole);
    pelt_headless_destroy(gl);
    return check_summary();
}
