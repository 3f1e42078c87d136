/* pelt render: a still, an image sequence or a video, headless. */
#include "apps/cli.h"
#include "apps/video.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* One terminal line: "[######     ]  60/240   23.5 fps  0:07 left", the
 * same for a PNG sequence and a video; the last one says the total time. */
static void progress(unsigned done, unsigned total, double elapsed)
{
    const int width = 30;
    int filled = (int)((double)done / total * width);
    int digits = snprintf(NULL, 0, "%u", total);
    double fps = elapsed > 0.0 ? done / elapsed : 0.0;
    double t = done == total ? elapsed : fps > 0.0 ? (total - done) / fps : 0.0;
    unsigned s = (unsigned)(t + 0.5);
    fprintf(stderr, "\r[%.*s%*s] %*u/%u  %6.1f fps  %u:%02u %s ", filled,
            "##############################", width - filled, "", digits, done, total, fps,
            s / 60, s % 60, done == total ? "total" : "left");
    if (done == total) fputc('\n', stderr);
    fflush(stderr);
}

/* Checks -o for the number of frames; prints the error. */
static bool check_output(const char *output, unsigned frames, bool video)
{
    char path[4096];
    if (video) {
        if (strchr(output, '%')) {
            cli_error("render", "-o '%s': a video is one file; frame patterns (%%04d) are for "
                      "PNG sequences", output);
            return false;
        }
        return true;
    }
    if (!cli_frame_path(output, 0, path, sizeof path)) {
        cli_error("render", "-o '%s': a frame pattern takes one %%d or %%0Nd and no other '%%'",
                  output);
        return false;
    }
    if (frames > 1 && !strchr(output, '%')) {
        cli_error("render", "-o '%s': %u frames need a pattern such as out_%%04d.png, or a "
                  "video such as out.mp4", output, frames);
        return false;
    }
    return true;
}

static bool write_mask(cli_session *s, const char *path)
{
    unsigned m = pelt_fur_mask_size(pelt_scene_instance_fur(s->instance));
    uint8_t *mask = malloc((size_t)m * m * 4);
    if (!mask) {
        cli_error("render", "out of memory for the mask picture");
        return false;
    }
    pelt_fur_mask_picture(pelt_scene_instance_fur(s->instance), mask);
    bool ok = cli_write_png("render", path, mask, m, m);
    free(mask);
    return ok;
}

int cmd_render(int argc, char **argv)
{
    cli_options o;
    int rc = cli_parse_command("render", argc, argv, &o);
    if (rc >= 0) return rc;
    const pelt_scene *sc = &o.scene;
    unsigned frames = sc->animation.frames ? sc->animation.frames : 1;
    float fps = sc->animation.fps > 0.0f ? sc->animation.fps : 30.0f;
    bool video = cli_video_is_video(o.output);
    char ffmpeg[4096];
    if (!check_output(o.output, frames, video)) {
        cli_options_free(&o);
        return 2;
    }
    if (video && !cli_video_check("render", o.output, ffmpeg, sizeof ffmpeg)) {
        cli_options_free(&o);
        return 1;
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
    cli_video v; /* ffmpeg starts last: nothing before the frames can fail now */
    if (video && !cli_video_open("render", ffmpeg, o.output, sc->output.width, sc->output.height,
                                 fps, &v)) {
        cli_session_close(&s);
        cli_options_free(&o);
        return 1;
    }
    bool show_progress = frames > 1 && !o.quiet && isatty(2);
    double start = seconds_now();
    unsigned shown = 0; /* frames the progress line has counted */
    char path[4096];
    rc = 0;
    for (unsigned i = 0; i < frames && rc == 0; i++) {
        if (i > 0) pelt_scene_instance_advance(s.instance, 1.0f / fps);
        if (!cli_session_draw(&s)) {
            rc = 1;
            break;
        }
        cli_session_read(&s);
        if (video) {
            if (!cli_video_write(&v, s.pixels)) rc = 1;
        } else {
            cli_frame_path(o.output, i, path, sizeof path);
            if (!cli_write_png("render", path, s.pixels, sc->output.width, sc->output.height))
                rc = 1;
        }
        if (show_progress && rc == 0) progress(++shown, frames, seconds_now() - start);
    }
    if (shown > 0 && shown < frames) fputc('\n', stderr); /* a message after the bar */
    if (video && !cli_video_close(&v)) rc = 1;
    if (rc == 0 && o.mask_out && !write_mask(&s, o.mask_out)) rc = 1;
    if (rc == 0 && !o.quiet && video)
        fprintf(stderr, "pelt render: wrote %s (%u frames at %g fps)\n", o.output, frames,
                (double)fps);
    else if (rc == 0 && !o.quiet && frames == 1)
        fprintf(stderr, "pelt render: wrote %s\n", path);
    cli_session_close(&s);
    cli_options_free(&o);
    return rc;
}
