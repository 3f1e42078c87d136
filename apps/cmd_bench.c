/* pelt bench: milliseconds per frame, median of repeated runs, with the
 * parts of a frame timed apart and variants measured in the same run.
 * Timings live here, never in tests. */
#include "apps/cli.h"

#include "gl/gl_api.h"
#include <math.h>
#include <stdlib.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct stats { double median, min, max; } stats;

static stats summarize(double *v, unsigned n)
{
    qsort(v, n, sizeof *v, cmp_double);
    stats s = {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v[0], v[n - 1]};
    return s;
}

static void print_stats(const char *name, stats s)
{
    printf("  %-12s median %9.3f ms  min %9.3f ms  max %9.3f ms\n", name, s.median, s.min, s.max);
}

enum { PART_STEP, PART_UPLOAD, PART_DRAW, PART_FRAME, PARTS };

/* Warm-up, then `frames` frames with the strand step, the upload of what
 * it changed and the draw timed apart (glFinish closes each GL part).
 * `t` holds PARTS * frames doubles of scratch. */
static void measure(cli_session *s, const pelt_scene *sc, unsigned warmup, unsigned frames,
                    double *t, stats out[PARTS])
{
    float fps = sc->animation.fps > 0.0f ? sc->animation.fps : 30.0f;
    for (unsigned i = 0; i < warmup; i++) {
        pelt_scene_instance_advance(s->instance, 1.0f / fps);
        cli_session_draw(s);
        glFinish();
    }
    for (unsigned i = 0; i < frames; i++) {
        double t0 = now_ms();
        pelt_scene_instance_advance(s->instance, 1.0f / fps);
        double t1 = now_ms();
        pelt_renderer_upload(s->renderer);
        glFinish();
        double t2 = now_ms();
        cli_session_draw(s);
        glFinish();
        double t3 = now_ms();
        t[PART_STEP * frames + i] = t1 - t0;
        t[PART_UPLOAD * frames + i] = t2 - t1;
        t[PART_DRAW * frames + i] = t3 - t2;
        t[PART_FRAME * frames + i] = t3 - t0;
    }
    for (int p = 0; p < PARTS; p++) out[p] = summarize(t + (size_t)p * frames, frames);
}

static void report(const char *title, const stats st[PARTS])
{
    static const char *names[PARTS] = {"strand step", "upload", "draw", "frame"};
    printf("%s\n", title);
    for (int p = 0; p < PARTS; p++) print_stats(names[p], st[p]);
    printf("  dynamics (step + upload) share of the frame: %.2f%%\n",
           100.0 * (st[PART_STEP].median + st[PART_UPLOAD].median) / st[PART_FRAME].median);
}

/* Draws one frame with `dd` and returns its milliseconds (glFinish). */
static double timed_draw(cli_session *s, const pelt_draw_desc *dd)
{
    pelt_draw_desc saved = s->draw;
    s->draw = *dd;
    double t0 = now_ms();
    cli_session_draw(s);
    glFinish();
    double t = now_ms() - t0;
    s->draw = saved;
    return t;
}

/* The fragments one draw shades: the fragment shader's invocations where GL
 * counts them (ARB_pipeline_statistics_query, core in 4.6; llvmpipe has
 * it), else the samples that pass the depth test and are not discarded. */
static double counted_draw(cli_session *s, const pelt_draw_desc *dd, bool invocations)
{
    GLenum target = invocations ? GL_FRAGMENT_SHADER_INVOCATIONS_ARB : GL_SAMPLES_PASSED;
    GLuint q = 0;
    glGenQueries(1, &q);
    glBeginQuery(target, q);
    timed_draw(s, dd);
    glEndQuery(target);
    GLuint64 n = 0;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &n);
    glDeleteQueries(1, &q);
    return (double)n;
}

/* --animation: the skinning of one frame on the CPU (pelt_mesh_pose, then
 * pelt_fur_set_pose hands it to the strands and the renderer), timed alone
 * and set against the frame; its upload is part of "upload" above. */
static int bench_skinning(cli_session *s, const pelt_scene *sc, unsigned frames, double frame_ms)
{
    const pelt_mesh *mesh = pelt_scene_instance_mesh(s->instance);
    pelt_fur *fur = pelt_scene_instance_fur(s->instance);
    size_t index, n = pelt_mesh_get_data(mesh).vertex_count;
    pelt_error err = {0};
    if (pelt_mesh_find_animation(mesh, sc->animation.name, &index, &err) != PELT_OK) {
        cli_error("bench", "%s", err.message);
        return 1;
    }
    pelt_animation_info info;
    pelt_mesh_animation(mesh, index, &info);
    float *pose = malloc(n * 10 * sizeof(float));
    double *t = calloc(frames, 2 * sizeof *t);
    if (!pose || !t) {
        free(pose);
        free(t);
        cli_error("bench", "out of memory");
        return 1;
    }
    for (unsigned i = 0; i < frames; i++) {
        float time = info.duration * (float)i / (float)frames;
        double t0 = now_ms();
        pelt_mesh_pose(mesh, index, time, pose, pose + 3 * n, pose + 6 * n, NULL);
        double t1 = now_ms();
        pelt_fur_set_pose(fur, pose, pose + 3 * n, pose + 6 * n, NULL);
        t[i] = t1 - t0;
        t[frames + i] = now_ms() - t0;
    }
    stats pose_st = summarize(t, frames), all = summarize(t + frames, frames);
    /* The alternative: the shells blend the bones themselves, per vertex
       and layer; both draws alternated, each from the same pose. */
    double *d = calloc(frames, 2 * sizeof *d);
    if (!d) {
        free(pose);
        free(t);
        cli_error("bench", "out of memory");
        return 1;
    }
    pelt_draw_desc in_vs = s->draw;
    in_vs.debug.skin_in_vertex_stage = true;
    for (unsigned i = 0; i < frames; i++) {
        d[i] = timed_draw(s, &s->draw);
        d[frames + i] = timed_draw(s, &in_vs);
    }
    stats once = summarize(d, frames), per_layer = summarize(d + frames, frames);
    free(d);
    pelt_skin_info sk = pelt_mesh_skin_info(mesh);
    printf("skinning '%s' on the CPU, %zu vertices (%zu skinned), %zu bones (median of %u):\n", info.name, n,
           sk.skinned_vertices, sk.bones, frames);
    print_stats("pose", pose_st);
    print_stats("pose + hand", all);
    printf("  skinning: %.2f%% of the frame (%.3f of %.3f ms), once a frame for skin, fins, shells and strands\n",
           100.0 * all.median / frame_ms, all.median, frame_ms);
    printf("the draw, alternated (median of %u each):\n", frames);
    print_stats("pose read", once);
    print_stats("skinned in VS", per_layer);
    printf("  skinning in the vertex stage, per vertex and layer: the draw takes %.3fx as long "
           "(%+.3f ms, against %.3f ms for the pose on the CPU)\n",
           per_layer.median / once.median, per_layer.median - once.median, all.median);
    free(pose);
    free(t);
    return 0;
}

/* 50 clumps whose discs cover a third of the mask (uv) area. */
static void add_third_of_clumps(pelt_fur *fur)
{
    const float radius = sqrtf(1.0f / (3.0f * 50.0f * 3.14159265f));
    pelt_rain r = {0.0f, radius, radius, 1.0f, 1.0f, 12345};
    pelt_fur_add_random_droplets(fur, &r, 50);
}

/* 10,000 droplets of radius 4 texels into a dry 2048^2 mask vs one whole
 * upload of that mask (RGBA32F), each the median of 9 runs. */
static int bench_droplets(const pelt_mesh *mesh)
{
    enum { MASK = 2048, DROPS = 10000, RUNS = 9 };
    pelt_fur *fur = NULL;
    pelt_error err = {0};
    pelt_fur_desc d = {.layers = 1, .look.texture_size = 8, .wet.mask_size = MASK};
    if (pelt_fur_create(mesh, &d, &fur, &err) != PELT_OK) {
        cli_error("bench", "%s", err.message);
        return 1;
    }
    float *whole = calloc((size_t)MASK * MASK, 4 * sizeof(float));
    pelt_droplet *list = calloc(DROPS, sizeof *list);
    if (!whole || !list) {
        free(whole);
        free(list);
        pelt_fur_destroy(fur);
        cli_error("bench", "out of memory");
        return 1;
    }
    /* Real texels in every page: an untouched calloc'd buffer would be the
     * kernel's shared zero page and upload unrealistically fast. */
    for (size_t i = 0; i < (size_t)MASK * MASK * 4; i++) whole[i] = (float)(i % 251) * (1.0f / 251.0f);
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, MASK, MASK, 0, GL_RGBA, GL_FLOAT, NULL);
    double drops[RUNS], upload[RUNS];
    const float r = 4.0f / MASK;
    for (int run = 0; run < RUNS; run++) {
        uint32_t x = 2463534242u + (uint32_t)run; /* xorshift: places made off the clock */
        for (int i = 0; i < DROPS; i++) {
            x ^= x << 13, x ^= x >> 17, x ^= x << 5;
            list[i] = (pelt_droplet){{(float)(x & 0xffff) / 65535.0f, (float)(x >> 16) / 65535.0f}, r, 0.8f};
        }
        pelt_fur_clear_wetness(fur); /* each run starts from dry fur */
        double t0 = now_ms();
        pelt_fur_add_droplets(fur, list, DROPS, NULL);
        drops[run] = now_ms() - t0;
        t0 = now_ms();
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, MASK, MASK, GL_RGBA, GL_FLOAT, whole);
        glFinish();
        upload[run] = now_ms() - t0;
    }
    stats sd = summarize(drops, RUNS), su = summarize(upload, RUNS);
    printf("droplets into a %dx%d mask (median of %d runs)\n", MASK, MASK, RUNS);
    print_stats("10k drops r=4", sd);
    print_stats("whole upload", su);
    printf("  10,000 droplets cost %.2fx one whole-mask upload\n", sd.median / su.median);
    glDeleteTextures(1, &tex);
    free(whole);
    free(list);
    pelt_fur_destroy(fur);
    return 0;
}

/* Comb strokes centred on vertices picked off the clock, at two radii:
 * the stroke alone (CPU) and the upload of the vertices it changed, each
 * the median over STROKES strokes. */
static int bench_brush(cli_session *s)
{
    enum { STROKES = 200 };
    pelt_fur *fur = pelt_scene_instance_fur(s->instance);
    const pelt_mesh *mesh = pelt_scene_instance_mesh(s->instance);
    const pelt_mesh_data md = pelt_mesh_get_data(mesh);
    const float diag = pelt_mesh_diagonal(mesh);
    double stroke[STROKES], upload[STROKES];
    printf("brush strokes on %zu vertices (median of %d strokes each):\n", md.vertex_count, STROKES);
    const float fractions[2] = {0.02f, 0.05f};
    for (int r = 0; r < 2; r++) {
        pelt_brush b = {.tool = PELT_BRUSH_COMB, .radius = fractions[r] * diag};
        size_t touched_sum = 0;
        uint32_t x = 88675123u; /* xorshift: centres chosen off the clock */
        for (int i = 0; i < STROKES; i++) {
            x ^= x << 13, x ^= x >> 17, x ^= x << 5;
            const float *c = md.positions + 3 * (size_t)(x % md.vertex_count);
            b.delta[0] = 0.01f * diag * ((i & 1) ? 1.0f : -1.0f);
            size_t touched = 0;
            double t0 = now_ms();
            pelt_fur_brush(fur, c, &b, &touched, NULL);
            double t1 = now_ms();
            pelt_renderer_upload(s->renderer);
            glFinish();
            stroke[i] = t1 - t0;
            upload[i] = now_ms() - t1;
            touched_sum += touched;
        }
        char name[32];
        snprintf(name, sizeof name, "r=%.0f%% stroke", 100.0 * fractions[r]);
        print_stats(name, summarize(stroke, STROKES));
        snprintf(name, sizeof name, "r=%.0f%% upload", 100.0 * fractions[r]);
        print_stats(name, summarize(upload, STROKES));
        printf("  %.0f vertices touched per stroke on average\n", (double)touched_sum / STROKES);
    }
    return 0;
}

/* Fragments and triangles per frame, split by pass from draws with and
 * without fins and shells (the shells test depth against the skin alone,
 * so the differences are each pass's own), and the time each fragment
 * takes: the pass's share of the alternated medians over its fragments. */
static void print_fragments(cli_session *s, const pelt_draw_desc *full, const pelt_draw_desc *no_fins,
                            const pelt_draw_desc *skin_only, double full_ms, double no_fins_ms, double skin_ms,
                            double floor_ms)
{
    bool inv = epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query");
    double skin = counted_draw(s, skin_only, inv);
    double shells = counted_draw(s, no_fins, inv) - skin;
    double fins = counted_draw(s, full, inv) - skin - shells;
    pelt_render_stats rs = pelt_renderer_get_stats(s->renderer);
    size_t shell_tris = (size_t)rs.shell_instances * rs.mesh_triangles;
    size_t fin_tris = rs.fins * 2 * rs.fin_rows;
    printf("  per frame (%s):\n", inv ? "fragment shader invocations" : "samples passed: fragments drawn");
    printf("    shells  %10zu triangles %12.0f fragments  %6.2f ns a fragment", shell_tris, shells,
           shells > 0.0 ? (no_fins_ms - skin_ms) * 1e6 / shells : 0.0);
    if (floor_ms > 0.0 && shells > 0.0) printf(" (%.2f in the floor shader)", (floor_ms - skin_ms) * 1e6 / shells);
    printf("\n    fins    %10zu triangles %12.0f fragments  %6.2f ns a fragment\n", fin_tris, fins,
           fins > 0.0 ? (full_ms - no_fins_ms) * 1e6 / fins : 0.0);
    printf("    skin    %10zu triangles %12.0f fragments\n", rs.triangles - shell_tris - fin_tris, skin);
}

/* Variants of the same frame drawn alternately, so the machine's noise hits
 * them alike: with and without fins (their share of the frame), the
 * back-facing shells in their place, with and
 * without the inter-fur shadows, every shell everywhere (no view budget),
 * the floor shader, the plain shell renderer, the frame as fur.lod = off
 * draws it, the shells blended without writing their depth, and with the
 * light's shadows on: without them and the light pass alone; with water,
 * the wet frame drawn with the dry shaders. */
static int bench_variants(cli_session *s, unsigned frames, const cli_options *o, bool wet, double step_ms)
{
    enum { FULL, NO_FINS, BACK_SHELLS, NO_INTER, FLAT, FLOOR, FLOOR_FINS, PLAIN, WET_WHOLE, NO_LIGHT, LIGHT_ONLY,
           SKIN_ONLY, LOD_OFF, NO_DEPTH, ONE_A_LAYER, ONE_PROGRAM, AS_DRY, NO_TUFT_BASE, VARIANTS };
    const bool with_floor = o->bench_floor, with_plain = o->bench_plain, with_lod_off = o->bench_lod_off;
    double *t = calloc((size_t)frames * VARIANTS, sizeof *t);
    if (!t) return 1;
    pelt_draw_desc v[VARIANTS];
    for (int k = 0; k < VARIANTS; k++) v[k] = s->draw;
    /* Without fins the back-facing shells would come back; keep them
     * culled so the difference is the fins alone. */
    v[NO_FINS].no_fins = true;
    v[NO_FINS].debug.cull_shells = 1;
    /* The silhouette drawn by the back-facing shells within the fur's
     * reach of it (fur.lod_back_reach) instead of the fins. */
    v[BACK_SHELLS].no_fins = true;
    v[BACK_SHELLS].debug.cull_shells = 0;
    v[NO_INTER].debug.no_inter_shadow = true;
    v[FLAT].debug.flat_shells = true;
    /* The floor: the skin and the same shells with a one-fetch shader. */
    v[FLOOR].no_fins = true;
    v[FLOOR].debug.cull_shells = 1;
    v[FLOOR].debug.floor_shader = true;
    /* The same scene with only the shell shader swapped: the fins drawn as
     * they are, so the ratio is the shell shader's alone. */
    v[FLOOR_FINS].debug.floor_shader = true;
    /* The yardstick: what the simplest shell renderer costs here (the
     * skin, then every shell along the normal with one fetch). */
    v[PLAIN].no_fins = true;
    v[PLAIN].debug.plain_shells = true;
    /* Every triangle with the wet shader, as before wet and dry were drawn apart. */
    v[WET_WHOLE].debug.no_wet_split = true;
    v[NO_LIGHT].debug.no_shadows = true;
    v[LIGHT_ONLY].no_skin = v[LIGHT_ONLY].no_fins = v[LIGHT_ONLY].debug.no_shells = true;
    /* The skin alone: what the shells' and the floor's times stand on. */
    v[SKIN_ONLY].no_fins = v[SKIN_ONLY].debug.no_shells = true;
    /* What level of detail saves: the same frame as fur.lod = off draws it. */
    v[LOD_OFF].debug.lod_off = true;
    /* The shells blended without writing their depth: what hiding the fur
     * behind the fur costs. */
    v[NO_DEPTH].debug.no_shell_depth = true;
    /* Each layer drawn once: what the sub shells cost, close up or wet. */
    v[ONE_A_LAYER].debug.no_sub_shells = true;
    /* Every triangle's shells with the program that reads across the gap:
     * what the view split saves. */
    v[ONE_PROGRAM].debug.no_view_split = true;
    /* The wet fur drawn with the dry shaders: the wet frame against the
     * dry one in the same run, alternated. */
    v[AS_DRY].debug.as_dry = true;
    /* Every wet layer with the tufts' program, even below their base. */
    v[NO_TUFT_BASE].debug.no_tuft_base = true;
    bool light = cli_session_has_shadows(s);
    bool fins = !s->draw.no_fins;
    (void)timed_draw(s, &v[FULL]);
    const pelt_render_stats drawn = pelt_renderer_get_stats(s->renderer);
    const bool sub = drawn.layer_shells > 1 || drawn.sub_shells > 0;
    const bool view_split = drawn.face_on_triangles > 0;
    bool run[VARIANTS] = {true, true, true, true, true, with_floor, with_floor && fins, with_plain, wet, light, light, true,
                           with_lod_off, true, sub, view_split, wet, wet};
    for (unsigned i = 0; i < frames; i++)
        for (int k = 0; k < VARIANTS; k++)
            if (run[k]) t[(size_t)k * frames + i] = timed_draw(s, &v[k]);
    stats st[VARIANTS];
    for (int k = 0; k < VARIANTS; k++)
        if (run[k]) st[k] = summarize(t + (size_t)k * frames, frames);
    printf("draw variants, alternated (median of %u each):\n", frames);
    print_stats("as drawn", st[FULL]);
    print_stats("no fins", st[NO_FINS]);
    print_stats("back shells", st[BACK_SHELLS]);
    print_stats("no inter-sh.", st[NO_INTER]);
    print_stats("flat shells", st[FLAT]);
    if (with_floor) print_stats("floor", st[FLOOR]);
    if (run[FLOOR_FINS]) print_stats("floor + fins", st[FLOOR_FINS]);
    if (with_plain) print_stats("plain", st[PLAIN]);
    if (wet) print_stats("wet whole", st[WET_WHOLE]);
    if (light) {
        print_stats("no light sh.", st[NO_LIGHT]);
        print_stats("light pass", st[LIGHT_ONLY]);
    }
    print_stats("skin alone", st[SKIN_ONLY]);
    print_stats("no depth", st[NO_DEPTH]);
    if (with_lod_off) print_stats("lod off", st[LOD_OFF]);
    if (sub) print_stats("one a layer", st[ONE_A_LAYER]);
    if (view_split) print_stats("one program", st[ONE_PROGRAM]);
    if (wet) print_stats("drawn dry", st[AS_DRY]);
    if (wet) print_stats("tufts' base", st[NO_TUFT_BASE]);
    print_fragments(s, &v[FULL], &v[NO_FINS], &v[SKIN_ONLY], st[FULL].median, st[NO_FINS].median,
                    st[SKIN_ONLY].median, with_floor ? st[FLOOR].median : 0.0);
    if (fins)
        printf("  fins: %.1f%% of the frame's draw\n", 100.0 * (1.0 - st[NO_FINS].median / st[FULL].median));
    printf("  the shells' depth (fur in front hides fur behind): the frame takes %.2fx as long as blended "
           "without it\n",
           st[FULL].median / st[NO_DEPTH].median);
    printf("  the view's shell budget: the frame takes %.2fx as long as with every shell everywhere\n",
           st[FULL].median / st[FLAT].median);
    if (with_floor)
        printf("  the frame takes %.2fx the floor (skin + the same shells with a one-fetch shader)\n",
               st[FULL].median / st[FLOOR].median);
    if (run[FLOOR_FINS])
        printf("  the frame takes %.2fx the floor with its fins (the same scene, only the shell shader "
               "swapped)\n",
               st[FULL].median / st[FLOOR_FINS].median);
    if (sub)
        printf("  sub shells (%u shells a layer close up, %u more wet): the frame takes %.2fx as long as one "
               "shell a layer\n",
               drawn.layer_shells, drawn.sub_shells, st[FULL].median / st[ONE_A_LAYER].median);
    if (view_split)
        printf("  face-on and side-on drawn apart (%zu of %zu triangles face-on, no read across the gap): the "
               "frame takes %.2fx as long as with one program\n",
               drawn.face_on_triangles, drawn.mesh_triangles, st[FULL].median / st[ONE_PROGRAM].median);
    if (wet) {
        printf("  wet and dry drawn apart: the frame takes %.2fx as long as with every triangle drawn wet\n",
               st[FULL].median / st[WET_WHOLE].median);
        printf("  the wet layers below the tufts' base drawn without the tufts: the frame takes %.2fx as long as "
               "with the tufts' program on every wet layer\n",
               st[FULL].median / st[NO_TUFT_BASE].median);
        printf("  the wet frame takes %.2fx as long as the same frame drawn dry (alternated)\n",
               st[FULL].median / st[AS_DRY].median);
    }
    if (with_plain)
        printf("  the frame takes %.2fx the plain shell renderer (every shell along the normal, one fetch, "
               "blended, no fins)\n",
               st[FULL].median / st[PLAIN].median);
    if (with_lod_off)
        printf("  level of detail: the draw takes 1/%.2f of fur.lod=off's; with the strand step (%.1f ms, the same "
               "in both) the frame takes 1/%.2f\n",
               st[LOD_OFF].median / st[FULL].median, step_ms,
               (st[LOD_OFF].median + step_ms) / (st[FULL].median + step_ms));
    bool shadows = pelt_fur_get_desc(pelt_scene_instance_fur(s->instance)).look.inter_shadow;
    if (shadows)
        printf("  inter-fur shadows: the draw takes %.3fx as long with them\n", st[FULL].median / st[NO_INTER].median);
    if (light)
        printf("  the light's shadows: %.1f%% of the frame's draw (the light pass alone %.1f%%, receiving "
               "them the rest; with the ground when it is on)\n",
               100.0 * (1.0 - st[NO_LIGHT].median / st[FULL].median),
               100.0 * st[LIGHT_ONLY].median / st[FULL].median);
    free(t);
    return 0;
}

/* The camera backs away along its view direction to `factor` times its
 * distance from the mesh's centre: each distance timed (alternated over
 * the distances, so noise hits them alike) with the levels of detail the
 * renderer chose there. */
static void bench_dolly(cli_session *s, unsigned frames)
{
    enum { STEPS = 7 };
    static const float factors[STEPS] = {1.0f, 1.5f, 2.0f, 3.0f, 4.0f, 8.0f, 16.0f};
    double *t = calloc((size_t)frames * STEPS, sizeof *t);
    if (!t) return;
    pelt_view base = pelt_scene_instance_view(s->instance);
    /* Distance to the mesh's origin along the view axis (view space -z). */
    float depth = -(base.view[2] * base.model[12] + base.view[6] * base.model[13] +
                    base.view[10] * base.model[14] + base.view[14]);
    pelt_render_stats rs[STEPS];
    for (unsigned i = 0; i < frames; i++)
        for (int k = 0; k < STEPS; k++) {
            pelt_view v = base;
            float back = depth * (factors[k] - 1.0f);
            v.view[14] -= back;
            for (int c = 0; c < 3; c++) v.eye[c] -= back * -base.view[2 + 4 * c];
            pelt_headless_bind(s->gl);
            glClearColor(s->background[0], s->background[1], s->background[2], s->background[3]);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            double t0 = now_ms();
            pelt_renderer_draw(s->renderer, &v, &s->draw);
            glFinish();
            t[(size_t)k * frames + i] = now_ms() - t0;
            rs[k] = pelt_renderer_get_stats(s->renderer);
        }
    printf("dolly out (draw, median of %u each, alternated):\n", frames);
    for (int k = 0; k < STEPS; k++) {
        stats st = summarize(t + (size_t)k * frames, frames);
        printf("  %5.1fx distance  median %9.3f ms  min %9.3f  max %9.3f   mesh level %u (%zu triangles), "
               "%u shells (level %u, blend %.2f)\n",
               (double)factors[k], st.median, st.min, st.max, rs[k].mesh_level, rs[k].mesh_triangles,
               rs[k].shell_instances, rs[k].shell_level, (double)rs[k].shell_blend);
    }
    free(t);
}

int cmd_bench(int argc, char **argv)
{
    cli_options o;
    int rc = cli_parse_command("bench", argc, argv, &o);
    if (rc >= 0) return rc;
    rc = 0;
    pelt_scene *sc = &o.scene;
    unsigned frames = sc->animation.frames > 1 ? sc->animation.frames : 30;
    cli_session s;
    if (!cli_session_open("bench", sc, &s)) {
        cli_options_free(&o);
        return 1;
    }
    double *t = calloc((size_t)frames * PARTS, sizeof *t);
    if (!t) {
        cli_error("bench", "out of memory");
        cli_session_close(&s);
        cli_options_free(&o);
        return 1;
    }
    const pelt_mesh *mesh = pelt_scene_instance_mesh(s.instance);
    pelt_fur *fur = pelt_scene_instance_fur(s.instance);
    pelt_scene_instance_stats is = pelt_scene_instance_get_stats(s.instance);
    pelt_mesh_stats ms = pelt_mesh_get_stats(mesh);
    pelt_fur_desc fd = pelt_fur_get_desc(fur);
    printf("pelt bench: %s\n", pelt_headless_renderer_name(s.gl));
    printf("scene: %zu triangles, %u layers, %ux%u, %ux MSAA, fur texture %u, mask %u, %u frames after %u "
           "warm-up\n",
           ms.triangle_count, fd.layers, sc->output.width, sc->output.height, sc->output.msaa,
           fd.look.texture_size, pelt_fur_mask_size(fur), frames, o.warmup);
    if (is.atlas_seconds > 0.0)
        printf("atlas build: %.3f s%s\n", is.atlas_seconds, is.atlas_from_cache ? " (from the cache)" : "");

    cli_session_drop_at(&s, &o);
    /* A strand reference that cannot be drawn (render.mode "strands") has
     * nothing to time: say so once, not every frame. */
    if (!cli_session_draw(&s)) {
        free(t);
        cli_session_close(&s);
        cli_options_free(&o);
        return 1;
    }
    stats plain[PARTS], wet[PARTS];
    measure(&s, sc, o.warmup, frames, t, plain);
    report(o.bench_clumps ? "as given (dry unless the scene wets it):" : "frame:", plain);
    pelt_render_stats rs = pelt_renderer_get_stats(s.renderer);
    printf("shell draw calls per frame: %u (%u layers, %u shells a layer close up, %u more wet sub shells), "
           "%zu triangles submitted\n",
           rs.shell_draw_calls, rs.shell_instances, rs.layer_shells, rs.sub_shells, rs.triangles);
    printf("level of detail: mesh level %u (%zu of %zu triangles), %zu fins drawn (%u rows) from level %u, "
           "%zu outline hairs, shell level %u (blend %.2f), back faces %s\n",
           rs.mesh_level, rs.mesh_triangles, ms.triangle_count, rs.fins, rs.fin_rows, rs.fin_level, rs.outline_hairs,
           rs.shell_level, (double)rs.shell_blend, rs.culled ? "culled" : "drawn");
    if (bench_variants(&s, frames, &o, false, plain[PART_STEP].median)) rc = 1;
    if (rc == 0 && sc->animation.name[0]) rc = bench_skinning(&s, sc, frames, plain[PART_FRAME].median);
    if (rc == 0 && o.bench_dolly) bench_dolly(&s, frames);
    if (o.bench_clumps) {
        add_third_of_clumps(fur);
        measure(&s, sc, o.warmup, frames, t, wet);
        report("with 50 clumps over a third of the surface:", wet);
        printf("wet sub shells per frame: %u (docs/wetness.md, Sub shells)\n",
               pelt_renderer_get_stats(s.renderer).sub_shells);
        printf("clumps cost %+.1f%% per frame (draw %+.1f%%)\n",
               100.0 * (wet[PART_FRAME].median / plain[PART_FRAME].median - 1.0),
               100.0 * (wet[PART_DRAW].median / plain[PART_DRAW].median - 1.0));
        printf("with the clumps, ");
        if (bench_variants(&s, frames, &o, true, wet[PART_STEP].median)) rc = 1;
    }
    if (o.bench_droplets) rc = bench_droplets(mesh);
    if (rc == 0 && o.bench_brush) rc = bench_brush(&s);
    free(t);
    cli_session_close(&s);
    cli_options_free(&o);
    return rc;
}
