/* pelt bench: milliseconds per frame, median of repeated runs. Timings
 * live here, never in tests. */
#include "apps/cli.h"

#include <epoxy/gl.h>
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

int cmd_bench(int argc, char **argv)
{
    cli_options o;
    int rc = cli_parse("bench", argc, argv, &o);
    if (rc) {
        cli_options_free(&o);
        return rc == 1 ? 0 : rc;
    }
    pelt_scene *sc = &o.scene;
    unsigned frames = sc->animation.frames > 1 ? sc->animation.frames : 30;
    cli_session s;
    if (!cli_session_open("bench", sc, &s)) {
        cli_options_free(&o);
        return 1;
    }
    double *draw = calloc(frames, sizeof *draw);
    if (!draw) {
        cli_error("bench", "out of memory");
        cli_session_close(&s);
        cli_options_free(&o);
        return 1;
    }
    float fps = sc->animation.fps > 0.0f ? sc->animation.fps : 30.0f;
    double *step = calloc(frames, sizeof *step), *upload = calloc(frames, sizeof *upload);
    for (unsigned i = 0; i < o.warmup; i++) {
        cli_session_advance(&s, sc, (float)i / fps, 1.0f / fps);
        cli_session_draw(&s, sc);
        glFinish();
    }
    /* Each part timed alone: the strand step on the CPU, the upload of what
     * it changed, then the draw; glFinish closes each GL part. */
    for (unsigned i = 0; i < frames && step && upload; i++) {
        double t0 = now_ms();
        cli_session_advance(&s, sc, (float)(o.warmup + i) / fps, 1.0f / fps);
        double t1 = now_ms();
        pelt_renderer_upload(s.renderer);
        glFinish();
        double t2 = now_ms();
        cli_session_draw(&s, sc);
        glFinish();
        double t3 = now_ms();
        step[i] = t1 - t0;
        upload[i] = t2 - t1;
        draw[i] = t3 - t2;
    }
    double *total = calloc(frames, sizeof *total);
    if (!step || !upload || !total) {
        cli_error("bench", "out of memory");
        free(step), free(upload), free(total), free(draw);
        cli_session_close(&s);
        cli_options_free(&o);
        return 1;
    }
    for (unsigned i = 0; i < frames; i++) total[i] = step[i] + upload[i] + draw[i];
    stats st = summarize(step, frames), up = summarize(upload, frames);
    stats d = summarize(draw, frames), tot = summarize(total, frames);
    pelt_mesh_stats ms = pelt_mesh_get_stats(s.mesh);
    pelt_fur_desc fd = pelt_fur_get_desc(s.fur);
    printf("pelt bench: %s\n", pelt_headless_renderer_name(s.gl));
    printf("scene: %zu triangles, %u layers, %ux%u, fur texture %u, %u frames after %u warm-up\n",
           ms.triangle_count, fd.layers, sc->output.width, sc->output.height, fd.texture_size,
           frames, o.warmup);
    const char *names[] = {"strand step", "upload", "draw", "frame"};
    const stats *all[] = {&st, &up, &d, &tot};
    for (int k = 0; k < 4; k++)
        printf("%-12s median %8.3f ms  min %8.3f ms  max %8.3f ms\n", names[k], all[k]->median,
               all[k]->min, all[k]->max);
    printf("dynamics share of the frame (step + upload): %.2f%%\n",
           100.0 * (st.median + up.median) / tot.median);
    printf("shell draw calls per frame: %u\n", pelt_renderer_shell_draw_calls(s.renderer));
    free(step), free(upload), free(total), free(draw);
    cli_session_close(&s);
    cli_options_free(&o);
    return 0;
}
