/* The soak: a long animation on a tiny image, everything the fur does at
 * once (rain, drying, gusty wind, a turntable, comb strokes, droplets by
 * ray), checking as it goes that no strand tip, groom or mask value
 * becomes NaN or infinite, that GL raises no error, and that resident
 * memory stays flat once warmed up.
 *   pelt_soak [STEPS [SIZE]]    default 1000 steps at 32 x 24
 * Prints the resident anonymous memory at the start (after the warm-up)
 * and the end and steps per second; exits 1 on any failure, 77 when there is no OpenGL. */
#define _POSIX_C_SOURCE 200809L
#include <pelt/pelt.h>

#include "core/fur/fur_gpu.h"
#include "core/fur/groom.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Resident anonymous memory in KiB (heap and mappings of the process's own
 * making; not the shared libraries, whose pages the kernel may drop and
 * bring back), from /proc/self/status. */
static long rss_kib(void)
{
    char line[256];
    long kib = -1;
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "RssAnon: %ld kB", &kib) == 1) break;
    fclose(f);
    return kib;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static bool all_finite(const float *v, size_t n, size_t *bad)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) {
            *bad = i;
            return false;
        }
    return true;
}

/* Every strand tip, groom value and mask texel is a finite number. */
static bool fur_is_finite(const pelt_fur *fur, long step)
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const pelt_mesh_data md = pelt_mesh_get_data(fs.mesh);
    size_t bad, stride = fs.groom_stride;
    const float *tips = fs.tips;
    if (!all_finite(tips, 3 * md.vertex_count, &bad)) {
        fprintf(stderr, "soak: step %ld: strand tip %zu is %g\n", step, bad / 3, tips[bad]);
        return false;
    }
    const float *mask = fs.mask;
    if (!all_finite(mask, 4 * (size_t)fs.mask_width * fs.mask_height, &bad)) {
        fprintf(stderr, "soak: step %ld: mask texel %zu is %g\n", step, bad / 4, mask[bad]);
        return false;
    }
    const unsigned char *groom = fs.groom;
    for (size_t v = 0; v < md.vertex_count; v++) {
        const pelt__groom_vertex *g = (const pelt__groom_vertex *)(groom + v * stride);
        float f[4] = {g->length, g->density, g->lean[0], g->lean[1]};
        if (!all_finite(f, 4, &bad)) {
            fprintf(stderr, "soak: step %ld: groom of vertex %zu is not finite\n", step, v);
            return false;
        }
    }
    return true;
}

/* Column-major rotation about Y by a radians. */
static void rotate_y(float a, float m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = cosf(a), m[2] = -sinf(a), m[5] = 1.0f, m[8] = sinf(a), m[10] = cosf(a), m[15] = 1.0f;
}

int main(int argc, char **argv)
{
    long steps = argc > 1 ? atol(argv[1]) : 1000;
    unsigned size = argc > 2 ? (unsigned)atoi(argv[2]) : 32;
    if (steps < 10 || size < 8) {
        fprintf(stderr, "usage: %s [STEPS >= 10 [SIZE >= 8]]\n", argv[0]);
        return 2;
    }
    unsigned w = size, h = size * 3 / 4;
    pelt_error err = {0};
    pelt_headless *gl = NULL;
    if (pelt_headless_create(&(pelt_headless_desc){w, h, 0, false}, &gl, &err) != PELT_OK) {
        fprintf(stderr, "soak: no OpenGL: %s\n", err.message);
        return 77;
    }
    pelt_mesh *mesh = NULL;
    pelt_fur *fur = NULL;
    pelt_renderer *renderer = NULL;
    int rc = 1;
    pelt_fur_desc fd = {.layers = 8, .seed = 11};
    fd.look.texture_size = 64;
    fd.wet.mask_size = 64;
    if (pelt_mesh_torus(1.0f, 0.4f, 32, 16, &mesh, &err) != PELT_OK ||
        pelt_fur_create(mesh, &fd, &fur, &err) != PELT_OK ||
        pelt_renderer_create(mesh, fur, NULL, &renderer, &err) != PELT_OK) {
        fprintf(stderr, "soak: %s\n", err.message);
        goto done;
    }
    pelt_view view = {0};
    pelt_camera_to_view(&(pelt_camera){.yaw = 30, .pitch = 25, .distance = 4.2f, .fov_y = 40},
                        (float)w / (float)h, &view);
    view.light = (pelt_light){{0.5f, 1.0f, 0.8f}, {1.0f, 1.0f, 1.0f}, 0.25f};
    view.width = w, view.height = h;
    pelt_fur_set_rain(fur, &(pelt_rain){.rate = 30.0f, .seed = 5});
    pelt_fur_set_dry_rate(fur, 0.05f);

    const float dt = 1.0f / 60.0f;
    const long warm = steps / 10 > 100 ? steps / 10 : 100 < steps ? 100 : steps / 2;
    long rss_start = 0, rss_peak = 0;
    double t0 = 0.0;
    uint32_t rng = 12345u;
    for (long i = 0; i < steps; i++) {
        float t = (float)i * dt;
        if (i == warm) {
            rss_start = rss_kib();
            t0 = now();
        }
        /* A turntable, and gusty wind that turns and changes strength. */
        rotate_y(0.8f * t, view.model);
        if (pelt_fur_set_transform(fur, view.model, &err) != PELT_OK) {
            fprintf(stderr, "soak: step %ld: %s\n", i, err.message);
            goto done;
        }
        pelt_forces forces = pelt_forces_default();
        forces.wind[0] = 6.0f * cosf(0.3f * t);
        forces.wind[2] = 6.0f * sinf(0.3f * t);
        forces.gust_strength = 0.8f;
        /* Rain on for 20 s, off for 20 s; the fur dries in between. */
        pelt_fur_set_rain_rate(fur, fmodf(t, 40.0f) < 20.0f ? 30.0f : 0.0f);
        pelt_fur_step(fur, dt, &forces);
        /* A comb stroke around the tube, then and now one against it. */
        if (i % 5 == 0) {
            float a = 0.37f * (float)i;
            float c[3] = {1.4f * cosf(a), 0.0f, 1.4f * sinf(a)};
            float s = i % 50 == 0 ? -1.0f : 1.0f;
            pelt_brush b = {.tool = PELT_BRUSH_COMB, .radius = 0.3f, .strength = 0.5f,
                            .delta = {-s * 0.05f * sinf(a), 0.02f * s, s * 0.05f * cosf(a)}};
            if (pelt_fur_brush(fur, c, &b, NULL, &err) != PELT_OK) {
                fprintf(stderr, "soak: step %ld: brush: %s\n", i, err.message);
                goto done;
            }
        }
        /* A droplet where a ray from above meets the torus. */
        if (i % 7 == 0) {
            rng = rng * 1664525u + 1013904223u;
            float x = ((float)(rng >> 8) / 16777216.0f - 0.5f) * 3.0f;
            rng = rng * 1664525u + 1013904223u;
            float z = ((float)(rng >> 8) / 16777216.0f - 0.5f) * 3.0f;
            float o[3] = {x, 3.0f, z}, d[3] = {0.0f, -1.0f, 0.0f};
            pelt_fur_add_droplet_ray(fur, o, d, 0.08f, i % 21 == 0 ? -0.5f : 0.8f);
        }
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        pelt_renderer_draw(renderer, &view, NULL);
        GLenum e = glGetError();
        if (e != GL_NO_ERROR) {
            fprintf(stderr, "soak: step %ld: GL error 0x%04x\n", i, e);
            goto done;
        }
        if ((i % 100 == 0 || i == steps - 1) && !fur_is_finite(fur, i)) goto done;
        if (i % 1000 == 0) glFinish(); /* keep the driver's queue short */
        long r = rss_kib();
        if (i >= warm && r > rss_peak) rss_peak = r;
    }
    glFinish();
    double seconds = now() - t0;
    long rss_end = rss_kib();
    long measured = steps - warm;
    printf("soak: %ld steps at %ux%u, %u triangles, %u layers\n", steps, w, h,
           (unsigned)pelt_mesh_get_data(mesh).triangle_count, fd.layers);
    printf("soak: anonymous RSS after %ld warm-up steps %ld KiB, at the end %ld KiB (peak %ld KiB, %+ld KiB)\n",
           warm, rss_start, rss_end, rss_peak, rss_end - rss_start);
    printf("soak: %.1f steps/s over the last %ld steps (%.1f s)\n", (double)measured / seconds,
           measured, seconds);
    /* Flat: growth after the warm-up within 4 MiB (allocator and driver
     * noise, and under ASan its quarantine), never growth with the steps. */
    long allowed = 4096;
    if (rss_end - rss_start > allowed) {
        fprintf(stderr, "soak: resident memory grew by %ld KiB after the warm-up (allowed %ld)\n",
                rss_end - rss_start, allowed);
        goto done;
    }
    printf("soak: no NaN or infinity, no GL error, memory flat\n");
    rc = 0;
done:
    pelt_renderer_destroy(renderer);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(mesh);
    pelt_headless_destroy(gl);
    return rc;
}
