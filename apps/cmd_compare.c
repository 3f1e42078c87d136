/* pelt compare: the shell picture against the strand reference, from the
 * same state of the same scene, measured (pelt/compare.h) and, with -o,
 * side by side: shells | strands | difference. */
#include "apps/cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The difference picture shows |shells - strands| this many times over. */
#define DIFF_GAIN 4

/* Draws the instance's current state with `draw` and reads it into out. */
static void draw_into(cli_session *s, const pelt_draw_desc *draw, uint8_t *out)
{
    pelt_draw_desc keep = s->draw;
    s->draw = *draw;
    cli_session_draw(s);
    pelt_headless_read_rgba8(s->gl, out);
    s->draw = keep;
}

/* Runs the scene to the frame that render would draw and draws it in
 * `mode`, in a session of its own: the strand reference supersampled and
 * multisampled as `render --strands` draws it (cli_session_open), the
 * shells as `render` does. With skin, the skin alone too (the outline).
 * Gives the fur's shell layers. */
static bool draw_state(const pelt_scene *scene, const cli_options *o, pelt_draw_mode mode, uint8_t *out,
                       uint8_t *skin, unsigned *layers)
{
    pelt_scene sc = *scene;
    sc.draw.mode = mode;
    cli_session s;
    if (!cli_session_open("compare", &sc, &s)) return false;
    cli_session_drop_at(&s, o);
    /* An animation compares its last frame, as render would draw it. */
    unsigned frames = sc.animation.frames ? sc.animation.frames : 1;
    float fps = sc.animation.fps > 0.0f ? sc.animation.fps : 30.0f;
    for (unsigned i = 1; i < frames; i++) pelt_scene_instance_advance(s.instance, 1.0f / fps);
    if (!cli_session_draw(&s)) {
        cli_session_close(&s);
        return false;
    }
    cli_session_read(&s);
    memcpy(out, s.pixels, (size_t)s.width * s.height * 4);
    *layers = pelt_fur_get_desc(pelt_scene_instance_fur(s.instance)).layers;
    if (skin) {
        pelt_draw_desc d = s.draw;
        d.no_skin = false;
        d.debug.no_shells = d.no_fins = true;
        draw_into(&s, &d, skin);
    }
    cli_session_close(&s);
    return true;
}

/* shells | strands | |shells - strands| x DIFF_GAIN, one row of three. */
static bool write_side(const char *path, const uint8_t *a, const uint8_t *b, unsigned w, unsigned h)
{
    uint8_t *side = malloc((size_t)w * 3 * h * 4);
    if (!side) {
        cli_error("compare", "out of memory for the %ux%u side-by-side picture", 3 * w, h);
        return false;
    }
    for (size_t y = 0; y < h; y++)
        for (size_t x = 0; x < w; x++) {
            size_t i = (y * w + x) * 4;
            uint8_t *row = side + y * w * 3 * 4;
            memcpy(row + x * 4, a + i, 4);
            memcpy(row + (w + x) * 4, b + i, 4);
            uint8_t *d = row + (2 * w + x) * 4;
            for (int c = 0; c < 3; c++) {
                int diff = abs((int)a[i + c] - (int)b[i + c]) * DIFF_GAIN;
                d[c] = (uint8_t)(diff > 255 ? 255 : diff);
            }
            d[3] = 255;
            row[x * 4 + 3] = row[(w + x) * 4 + 3] = 255;
        }
    bool ok = cli_write_png("compare", path, side, 3 * w, h);
    free(side);
    return ok;
}

static void print_bands(const char *name, const double *v)
{
    printf("%s", name);
    for (int k = 0; k < PELT_COMPARE_BANDS; k++) printf(" %.4f", v[k]);
    printf("\n");
}

static void print_result(const pelt_compare_result *r, unsigned layers)
{
    printf("ssim %.4f\n", r->ssim);
    printf("mae %.3f\n", r->mae);
    printf("silhouette_px");
    for (int k = 0; k < PELT_COMPARE_BANDS; k++) printf(" %g", (double)r->silhouette_px[k]);
    printf("\n");
    print_bands("silhouette_shells", r->silhouette_shells);
    print_bands("silhouette_strands", r->silhouette_strands);
    printf("extent_shells_px %.0f\n", (double)r->extent_shells_px);
    printf("extent_strands_px %.0f\n", (double)r->extent_strands_px);
    printf("fur_px %.2f\n", (double)r->fur_px);
    printf("stripe_frequency %.4f\n", r->fur_px > 0.0f ? layers / (double)r->fur_px : NAN);
    printf("stripe_band %.4f 0.5\n", r->stripe_frequency);
    printf("stripe_shells %.4g\n", r->stripe_shells);
    printf("stripe_strands %.4g\n", r->stripe_strands);
    printf("stripe_energy_ratio %.3f\n", r->stripe_energy_ratio);
    printf("outline_grain_shells %.3f\n", r->outline_grain_shells);
    printf("outline_grain_strands %.3f\n", r->outline_grain_strands);
    printf("outline_grain_ratio %.3f\n", r->outline_grain_ratio);
    printf("outline_radial_shells %.3f\n", r->outline_radial_shells);
    printf("outline_radial_strands %.3f\n", r->outline_radial_strands);
    printf("outline_luminance_shells %.2f\n", r->outline_luminance_shells);
    printf("outline_luminance_strands %.2f\n", r->outline_luminance_strands);
    printf("luminance_shells %.2f\n", r->luminance_shells);
    printf("luminance_strands %.2f\n", r->luminance_strands);
    fflush(stdout);
}

static uint8_t to_byte(float v)
{
    float c = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
    return (uint8_t)lroundf(c * 255.0f);
}

int cmd_compare(int argc, char **argv)
{
    cli_options o;
    int rc = cli_parse_command("compare", argc, argv, &o);
    if (rc >= 0) return rc;
    const pelt_scene *sc = &o.scene;
    if (sc->ground.enabled) {
        cli_error("compare", "ground.enabled: the ground would count as fur outside the "
                  "skin's outline; compare a scene without it");
        cli_options_free(&o);
        return 2;
    }
    if (o.output_set && strchr(o.output, '%')) {
        cli_error("compare", "-o '%s': compare writes one picture (shells | strands | "
                  "difference), not a frame pattern", o.output);
        cli_options_free(&o);
        return 2;
    }
    unsigned w = sc->output.width, h = sc->output.height;
    size_t bytes = (size_t)w * h * 4;
    uint8_t *shells = malloc(bytes), *strands = malloc(bytes), *skin = malloc(bytes);
    rc = 0;
    if (!shells || !strands || !skin) {
        cli_error("compare", "out of memory for three %ux%u pictures", w, h);
        rc = 1;
    }
    /* The same scene run twice from its seed: the same state each time. */
    unsigned layers = 0;
    if (rc == 0 && (!draw_state(sc, &o, PELT_DRAW_SHELLS, shells, skin, &layers) ||
                    !draw_state(sc, &o, PELT_DRAW_STRANDS, strands, NULL, &layers)))
        rc = 1;
    if (rc == 0) {
        pelt_compare_desc cd = {.shells = {shells, w, h}, .strands = {strands, w, h},
                                .skin = {skin, w, h}, .fur_px = o.fur_px, .layers = layers};
        for (int c = 0; c < 3; c++) cd.background[c] = to_byte(sc->output.background[c]);
        pelt_compare_result r;
        pelt_error err = {0};
        if (pelt_compare_images(&cd, &r, &err) != PELT_OK) {
            cli_error("compare", "%s", err.message);
            rc = 1;
        } else {
            printf("reference strands\n");
            print_result(&r, layers);
            if (o.output_set && !write_side(o.output, shells, strands, w, h)) rc = 1;
            else if (o.output_set && !o.quiet)
                fprintf(stderr, "pelt compare: wrote %s (shells | strands | difference x%d)\n",
                        o.output, DIFF_GAIN);
        }
    }
    free(shells);
    free(strands);
    free(skin);
    cli_options_free(&o);
    return rc;
}
