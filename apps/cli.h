/* The pelt command: shared pieces of its subcommands. */
#ifndef PELT_CLI_H
#define PELT_CLI_H

#include "pelt/pelt.h"

#include <stdio.h>

/* Reports an error as "pelt CMD: message" on stderr. */
void cli_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#define CLI_MAX_DROPS 64

/* Options shared by render and bench, parsed into a scene. */
typedef struct cli_options {
    pelt_scene scene;
    const char *output;    /* -o FILE or pattern with %d / %0Nd */
    const char *mask_out;  /* --mask-out FILE */
    const char *groom_out; /* --save-groom FILE */
    unsigned warmup;       /* bench */
    unsigned repeats;      /* bench: measured frames */
    float drops[CLI_MAX_DROPS][3];    /* --drop-at: pixel x, pixel y, world radius */
    int drop_count;
    bool bench_clumps;     /* bench --clumps */
    bool bench_droplets;   /* bench --droplets */
    bool bench_brush;      /* bench --brush */
    bool quiet;
} cli_options;

/* Parses argv (after the subcommand) into `o`: an optional scene file
 * first, then flags that override it. Prints help and returns 1 for -h;
 * prints a message naming the flag and returns 2 for bad input; returns
 * 0 when parsed. */
int cli_parse(const char *cmd, int argc, char **argv, cli_options *o);
void cli_options_free(cli_options *o);

/* A scene instance (the library's scene runner) drawn into a headless
 * context: what render and bench share. */
typedef struct cli_session {
    const char *cmd;               /* "render", "bench": starts messages */
    pelt_scene_instance *instance;
    pelt_headless *gl;
    pelt_renderer *renderer;
    float background[4];
    uint8_t *pixels;               /* width * height * 4 */
} cli_session;

/* Instantiates the scene, makes the context and the renderer. Prints the
 * error and returns false on failure (everything made so far is freed).
 * Warnings print as "pelt CMD: warning: ...". */
bool cli_session_open(const char *cmd, const pelt_scene *scene, cli_session *s);
void cli_session_close(cli_session *s);

/* Drops water where the rays through the --drop-at pixels hit the mesh;
 * prints a warning for a ray that misses. */
void cli_session_drop_at(cli_session *s, const cli_options *o);

/* Clears and draws the instance's current state. */
void cli_session_draw(cli_session *s);

/* Writes RGBA8 rows (top first) as PNG; prints the error on failure. */
bool cli_write_png(const char *cmd, const char *path, const uint8_t *rgba, unsigned w, unsigned h);

/* Expands a frame pattern ("out_%04d.png"); false if the pattern is not a
 * single %d / %0Nd conversion (a pattern without one is taken as is) or
 * the result does not fit. */
bool cli_frame_path(const char *pattern, unsigned frame, char *out, size_t out_size);

int cmd_render(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_atlas(int argc, char **argv);

#endif
