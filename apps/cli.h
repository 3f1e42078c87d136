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

/* One flag of a command as help, the manual page and shell completion show
 * it: all three read the same tables, so they cannot drift apart. */
typedef struct cli_flag_doc {
    const char *name;    /* "--output" */
    const char *alias;   /* "-o", or NULL */
    const char *metavar; /* "FILE"; NULL for a flag without a value */
    const char *help;
    const char *values;  /* words a completion offers as the value, or NULL */
} cli_flag_doc;

/* Fills *out with the i-th flag of a command; false past the last. */
typedef bool (*cli_flag_list)(size_t i, cli_flag_doc *out);

/* A subcommand of pelt. */
typedef struct cli_command {
    const char *name;
    const char *args;        /* "[SCENE.json] [flags]" */
    const char *summary;     /* one line for `pelt --help` */
    const char *description; /* what `pelt NAME --help` and the manual say */
    cli_flag_list flags;     /* NULL: no flags but -h */
    int (*run)(int argc, char **argv);
    const char *arg_files;   /* completion: a glob of files for the argument, or NULL */
    const char *arg_words;   /* completion: words for the argument, or NULL */
    bool hidden;             /* run by the build, not listed */
} cli_command;

/* Every subcommand, NULL-named last (apps/commands.c). */
extern const cli_command cli_commands[];
const cli_command *cli_find_command(const char *name);

/* Prints `pelt NAME --help` from the command's table entry. */
void cli_print_help(FILE *f, const cli_command *c);

/* The flags of render and bench (apps/options.c) and of atlas. */
bool cli_scene_flag(size_t i, cli_flag_doc *out);
bool cli_atlas_flag(size_t i, cli_flag_doc *out);

#define CLI_MAX_DROPS 64

/* Options shared by render, bench and compare, parsed into a scene. */
typedef struct cli_options {
    pelt_scene scene;
    const char *output;    /* -o FILE or pattern with %d / %0Nd */
    bool output_set;       /* -o was given (compare writes a picture only then) */
    const char *mask_out;  /* --mask-out FILE */
    const char *groom_out; /* --save-groom FILE */
    unsigned warmup;       /* bench */
    unsigned repeats;      /* bench: measured frames */
    float drops[CLI_MAX_DROPS][3];    /* --drop-at: pixel x, pixel y, world radius */
    int drop_count;
    bool bench_clumps;     /* bench --clumps */
    bool bench_droplets;   /* bench --droplets */
    bool bench_brush;      /* bench --brush */
    bool bench_floor;      /* bench --floor */
    bool bench_plain;      /* bench --plain */
    bool bench_lod_off;    /* bench --lod-off */
    bool bench_dolly;      /* bench --dolly */
    float fur_px;          /* compare --fur-px; 0: from the camera */
    bool quiet;
} cli_options;

/* Parses argv (after the subcommand) into `o`: an optional scene file
 * first, then flags that override it. Prints help and returns 1 for -h;
 * prints a message naming the flag and returns 2 for bad input; returns
 * 0 when parsed. */
int cli_parse(const char *cmd, int argc, char **argv, cli_options *o);
/* cli_parse for a command's entry point: -1 to go on with *o, else the
 * command's exit code (0 after --help) with *o already freed. */
int cli_parse_command(const char *cmd, int argc, char **argv, cli_options *o);
void cli_options_free(cli_options *o);

/* A scene instance (the library's scene runner) drawn into a headless
 * context: what render and bench share. */
typedef struct cli_session {
    const char *cmd;               /* "render", "bench": starts messages */
    pelt_scene_instance *instance;
    pelt_headless *gl;
    pelt_renderer *renderer;
    float background[4];
    pelt_draw_desc draw;           /* the scene's passes (draw.*) */
    uint8_t *pixels;               /* width * height * 4 */
    unsigned samples;              /* the strand reference: drawn at samples x the size */
    uint8_t *big;                  /* then read here and box-filtered into pixels */
    unsigned width, height;        /* the output's size */
    bool shadows;                  /* the light's shadows are on (shadows.enabled) */
} cli_session;

/* Instantiates the scene, makes the context and the renderer. Prints the
 * error and returns false on failure (everything made so far is freed).
 * Warnings print as "pelt CMD: warning: ...". */
bool cli_session_open(const char *cmd, const pelt_scene *scene, cli_session *s);
void cli_session_close(cli_session *s);
/* Reads the drawn frame into s->pixels (box-filtered down from the strand
 * reference's larger framebuffer). */
void cli_session_read(cli_session *s);
/* Whether the scene turned the light's shadows on. */
bool cli_session_has_shadows(const cli_session *s);

/* Drops water where the rays through the --drop-at pixels hit the mesh;
 * prints a warning for a ray that misses. */
void cli_session_drop_at(cli_session *s, const cli_options *o);

/* Clears and draws the instance's current state. Prints the error and
 * returns false when the strand reference was asked for and could not be
 * drawn. */
bool cli_session_draw(cli_session *s);

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
int cmd_compare(int argc, char **argv);    /* apps/cmd_compare.c */
int cmd_view(int argc, char **argv);       /* apps/cmd_view.c */
bool cli_view_flag(size_t i, cli_flag_doc *out); /* render's flags and the viewer's */
int cmd_completion(int argc, char **argv); /* apps/completion.c */
int cmd_manpage(int argc, char **argv);    /* apps/manpage.c */

#endif
