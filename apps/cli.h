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
    unsigned warmup;       /* bench */
    unsigned repeats;      /* bench: measured frames */
    float drops[CLI_MAX_DROPS][3];    /* --drop-at: pixel x, pixel y, world radius */
    int drop_count;
    bool bench_clumps;     /* bench --clumps */
    bool bench_droplets;   /* bench --droplets */
    bool quiet;
} cli_options;

/* Parses argv (after the subcommand) into `o`: an optional scene file
 * first, then flags that override it. Prints help and returns 1 for -h;
 * prints a message naming the flag and returns 2 for bad input; returns
 * 0 when parsed. */
int cli_parse(const char *cmd, int argc, char **argv, cli_options *o);
void cli_options_free(cli_options *o);

/* Loaded state for rendering a scene headless. */
typedef struct cli_session {
    pelt_mesh *mesh;
    pelt_fur *fur;
    pelt_headless *gl;
    pelt_renderer *renderer;
    pelt_view view;
    uint8_t *pixels; /* width * height * 4 */
    double atlas_seconds; /* atlas build time, 0 when none was built */
    bool atlas_from_cache;
    bool settled;         /* past the settling before the first frame */
} cli_session;

/* Loads the mesh, makes the fur, the context and the renderer. Prints the
 * error and returns false on failure (everything made so far is freed). */
bool cli_session_open(const char *cmd, const pelt_scene *scene, cli_session *s);
void cli_session_close(cli_session *s);

/* Drops water where the rays through the --drop-at pixels hit the mesh;
 * prints a warning for a ray that misses. */
void cli_session_drop_at(cli_session *s, const cli_options *o);

/* Moves the mesh to where the scene has it at time t and steps the fur by
 * dt under the scene's forces at t. */
void cli_session_advance(cli_session *s, const pelt_scene *scene, float t, float dt);

/* Clears and draws the current state. */
void cli_session_draw(cli_session *s, const pelt_scene *scene);

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
