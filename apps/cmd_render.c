/* pelt render: a still or an image sequence, headless. */
#include "apps/cli.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void progress(unsigned done, unsigned total)
{
    const int width = 40;
    int filled = (int)((double)done / total * width);
    fprintf(stderr, "\r[%.*s%*s] %u/%u", filled, "########################################",
            width - filled, "", done, total);
    if (done == total) fputc('\n', stderr);
    fflush(stderr);
}

int cmd_render(int argc, char **argv)
{
    cli_options o;
    int rc = cli_parse("render", argc, argv, &o);
    if (rc) {
        cli_options_free(&o);
        return rc == 1 ? 0 : rc;
    }
    const pelt_scene *sc = &o.scene;
    unsigned frames = sc->animation.frames ? sc->animation.frames : 1;
    char path[4096];
    if (!cli_frame_path(o.output, 0, path, sizeof path)) {
        cli_error("render", "-o '%s': a frame pattern takes one %%d or %%0Nd and no other '%%'",
                  o.output);
        cli_options_free(&o);
        return 2;
    }
    if (frames > 1 && !strchr(o.output, '%')) {
        cli_error("render", "-o '%s': %u frames need a pattern such as out_%%04d.png", o.output,
                  frames);
        cli_options_free(&o);
        return 2;
    }
    cli_session s;
    if (!cli_session_open("render", sc, &s)) {
        cli_options_free(&o);
        return 1;
    }
    cli_session_drop_at(&s, &o);
    if (o.groom_out) {
        pelt_error gerr = {0};
        if (pelt_fur_save_groom(pelt_scene_instance_fur(s.instance), o.groom_out, &gerr) != PELT_OK) {
            cli_error("render", "--save-groom: %s", gerr.message);
            cli_session_close(&s);
            cli_options_free(&o);
            return 1;
        }
    }
    bool show_progress = frames > 1 && !o.quiet && isatty(2);
    float fps = sc->animation.fps > 0.0f ? sc->animation.fps : 30.0f;
    rc = 0;
    for (unsigned i = 0; i < frames && rc == 0; i++) {
        if (i > 0) pelt_scene_instance_advance(s.instance, 1.0f / fps);
        cli_session_draw(&s);
        pelt_headless_read_rgba8(s.gl, s.pixels);
        cli_frame_path(o.output, i, path, sizeof path);
        if (!cli_write_png("render", path, s.pixels, sc->output.width, sc->output.height)) rc = 1;
        if (show_progress) progress(i + 1, frames);
    }
    if (rc == 0 && o.mask_out) {
        unsigned m = pelt_fur_mask_size(pelt_scene_instance_fur(s.instance));
        uint8_t *mask = malloc((size_t)m * m * 4);
        if (!mask) {
            cli_error("render", "out of memory for the mask picture");
            rc = 1;
        } else {
            pelt_fur_mask_picture(pelt_scene_instance_fur(s.instance), mask);
            if (!cli_write_png("render", o.mask_out, mask, m, m)) rc = 1;
            free(mask);
        }
    }
    if (rc == 0 && !o.quiet && frames == 1) fprintf(stderr, "pelt render: wrote %s\n", path);
    cli_session_close(&s);
    cli_options_free(&o);
    return rc;
}
