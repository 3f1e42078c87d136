/* The scene runner drawn into a headless context, for render and bench. */
#include "apps/cli.h"

#include "gl/gl_api.h"
#include <stdlib.h>
#include <string.h>

/* The least multisampling of the strand reference: 4 is what every GL 3.3
 * implementation must offer (GL_MAX_SAMPLES >= 4). */
enum { STRAND_MSAA = 4 };

/* The most shell layers drawn into an 8-bit colour target (below). */
enum { SESSION_8BIT_LAYERS = 32 };

static void print_warning(pelt_log_level level, const char *message, void *user)
{
    const char *cmd = user;
    if (level <= PELT_LOG_WARNING)
        fprintf(stderr, "pelt %s: %s%s\n", cmd, level == PELT_LOG_WARNING ? "warning: " : "", message);
}

bool cli_session_open(const char *cmd, const pelt_scene *sc, cli_session *s)
{
    memset(s, 0, sizeof *s);
    s->cmd = cmd;
    memcpy(s->background, sc->output.background, sizeof s->background);
    s->draw = sc->draw;
    /* The strand reference's hairs are opaque and thinner than a pixel:
     * drawn at samples x the size, averaged down for coverage. */
    s->samples = s->draw.mode == PELT_DRAW_STRANDS && sc->strand_samples > 1 ? sc->strand_samples : 1;
    s->width = sc->output.width, s->height = sc->output.height;
    pelt_error err = {0};
    pelt_scene_instance_desc idesc = {.hooks.logger = {print_warning, (void *)cmd}};
    if (pelt_scene_instantiate(sc, &idesc, &s->instance, &err) != PELT_OK) {
        cli_error(cmd, "%s", err.message);
        return false;
    }
    /* ... and multisampled (at least STRAND_MSAA samples) so that doubling the
     * supersampling changes the picture by less than 1/255 (docs/reference.md). */
    unsigned msaa = sc->output.msaa;
    if (s->draw.mode == PELT_DRAW_STRANDS && msaa < STRAND_MSAA) msaa = STRAND_MSAA;
    pelt_headless_desc hd = {sc->output.width * s->samples, sc->output.height * s->samples, msaa, false, false};
    /* Each shell blends into the colour target: an 8-bit target rounds
     * every blend, and over more than 32 layers of small coverage the
     * rounding adds up to speckles of another hue (docs/reference.md, At
     * high quality). A half-float target takes them; it costs about a
     * tenth of the frame on llvmpipe, so 32 layers keep the 8-bit one. */
    hd.half_float_target = s->draw.mode != PELT_DRAW_STRANDS &&
                           pelt_fur_get_desc(pelt_scene_instance_fur(s->instance)).layers > SESSION_8BIT_LAYERS;
    if (pelt_headless_create(&hd, &s->gl, &err) != PELT_OK ||
        pelt_renderer_create(pelt_scene_instance_mesh(s->instance),
                             pelt_scene_instance_fur(s->instance), NULL, &s->renderer,
                             &err) != PELT_OK) {
        cli_error(cmd, "%s", err.message);
        cli_session_close(s);
        return false;
    }
    if (pelt_renderer_set_shadows(s->renderer, &sc->shadows, &err) != PELT_OK) {
        cli_error(cmd, "shadows: %s", err.message);
        cli_session_close(s);
        return false;
    }
    pelt_renderer_set_ground(s->renderer, &sc->ground);
    s->shadows = sc->shadows.enabled;
    s->pixels = malloc((size_t)sc->output.width * sc->output.height * 4);
    if (s->samples > 1) s->big = malloc((size_t)hd.width * hd.height * 4);
    if (!s->pixels || (s->samples > 1 && !s->big)) {
        cli_error(cmd, "out of memory for a %ux%u image", sc->output.width, sc->output.height);
        cli_session_close(s);
        return false;
    }
    return true;
}

bool cli_session_has_shadows(const cli_session *s) { return s->shadows; }

void cli_session_close(cli_session *s)
{
    pelt_renderer_destroy(s->renderer);
    pelt_headless_destroy(s->gl);
    pelt_scene_instance_destroy(s->instance);
    free(s->pixels);
    free(s->big);
    memset(s, 0, sizeof *s);
}

void cli_session_read(cli_session *s)
{
    if (s->samples <= 1) {
        pelt_headless_read_rgba8(s->gl, s->pixels);
        return;
    }
    pelt_headless_read_rgba8(s->gl, s->big);
    const unsigned k = s->samples, bw = s->width * k;
    for (unsigned y = 0; y < s->height; y++)
        for (unsigned x = 0; x < s->width; x++)
            for (unsigned c = 0; c < 4; c++) {
                unsigned sum = 0;
                for (unsigned j = 0; j < k; j++)
                    for (unsigned i = 0; i < k; i++)
                        sum += s->big[(((size_t)y * k + j) * bw + (size_t)x * k + i) * 4 + c];
                s->pixels[((size_t)y * s->width + x) * 4 + c] = (uint8_t)((sum + k * k / 2) / (k * k));
            }
}

void cli_session_drop_at(cli_session *s, const cli_options *o)
{
    for (int i = 0; i < o->drop_count; i++) {
        const float *d = o->drops[i];
        if (!pelt_scene_instance_drop_at_pixel(s->instance, d[0], d[1], d[2], 1.0f))
            fprintf(stderr, "pelt: warning: --drop-at %g,%g misses the mesh\n", (double)d[0],
                    (double)d[1]);
    }
}

bool cli_session_draw(cli_session *s)
{
    pelt_headless_bind(s->gl);
    const float *bg = s->background;
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_view view = pelt_scene_instance_view(s->instance);
    pelt_renderer_draw(s->renderer, &view, &s->draw);
    /* A picture without the hairs it was asked for is not a reference: the
     * logger printed why, this stops the command. */
    if (pelt_renderer_get_stats(s->renderer).strand_failures) {
        cli_error(s->cmd, "the strand reference could not be drawn (see the error above)");
        return false;
    }
    return true;
}
