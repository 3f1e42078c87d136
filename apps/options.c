/* Flags shared by `pelt render` and `pelt bench`: each names a scene key
 * (set through pelt_scene_set, so flags and scene files validate alike). */
#include "apps/cli.h"

#include "pelt/params.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void cli_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "pelt %s: ", cmd);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

typedef enum flag_kind {
    FLAG_KEY,     /* value goes to a scene key as is */
    FLAG_SWITCH,  /* no value: `key` is KEY=VALUE, set as --set would */
    FLAG_VEC3,    /* "X,Y,Z" goes to a scene key as [X,Y,Z] */
    FLAG_SIZE,    /* "WxH" */
    FLAG_MESH,    /* torus | sphere | square | FILE */
    FLAG_SET,     /* key=value */
    FLAG_OUTPUT,  /* -o */
    FLAG_MASK_OUT,
    FLAG_GROOM_OUT,
    FLAG_WARMUP,
    FLAG_DROP_AT,
    FLAG_CLUMPS,
    FLAG_DROPLETS,
    FLAG_BRUSH,
    FLAG_FLOOR,
    FLAG_PLAIN,
    FLAG_DOLLY,
    FLAG_LOD_OFF,
    FLAG_FUR_PX,
    FLAG_QUIET
} flag_kind;

typedef struct flag {
    const char *name, *alias, *metavar;
    flag_kind kind;
    const char *key;
    const char *help;
    const char *values; /* words shell completion offers as the value */
} flag;

static const flag flags[] = {
    {"--output", "-o", "FILE", FLAG_OUTPUT, NULL,
     "PNG; for --frames > 1 a pattern like out_%04d.png, or a video "
     "out.mp4/.webm/.gif through ffmpeg (default pelt.png)"},
    {"--mesh", NULL, "FILE|torus|sphere|square", FLAG_MESH, NULL, "mesh file (OBJ, PLY, OFF, STL, glTF...) or a procedural shape",
     "torus sphere square"},
    {"--layers", NULL, "N", FLAG_KEY, "fur.layers", "shell layers edge-on; half of them face-on (default 32)"},
    {"--length", NULL, "L", FLAG_KEY, "fur.length", "fur length in world units (default 3% of the mesh diagonal)"},
    {"--density", NULL, "D", FLAG_KEY, "fur.density", "strands per fur-texture tile (default 3000)"},
    {"--texture-size", NULL, "N", FLAG_KEY, "fur.texture_size", "fur texture size (default 256)"},
    {"--seed", NULL, "S", FLAG_KEY, "fur.seed", "seed of the fur texture and dynamics (default 1)"},
    {"--size", NULL, "WxH", FLAG_SIZE, NULL, "image size in pixels (default 800x600)"},
    {"--msaa", NULL, "N", FLAG_KEY, "output.msaa", "multisample anti-aliasing samples (default 4, 0 = off)"},
    {"--texture", NULL, "FILE", FLAG_KEY, "texture.image", "colour texture image (PNG, JPEG...)"},
    {"--pattern", NULL, "NAME", FLAG_KEY, "texture.pattern", "procedural colour: none, spots, stripes, noise",
     "none spots stripes noise"},
    {"--yaw", NULL, "DEG", FLAG_KEY, "camera.yaw", "orbit camera yaw"},
    {"--pitch", NULL, "DEG", FLAG_KEY, "camera.pitch", "orbit camera pitch"},
    {"--distance", NULL, "D", FLAG_KEY, "camera.distance", "orbit camera distance"},
    {"--fov", NULL, "DEG", FLAG_KEY, "camera.fov_y", "vertical field of view"},
    {"--light", NULL, "X,Y,Z", FLAG_VEC3, "light.direction", "direction towards the light"},
    {"--frames", NULL, "N", FLAG_KEY, "animation.frames", "frames to render (bench: frames to time)"},
    {"--fps", NULL, "F", FLAG_KEY, "animation.fps", "frames per second of the animation (default 30)"},
    {"--turntable", NULL, "DEG/S", FLAG_KEY, "animation.turntable", "spin the mesh about +Y"},
    {"--animation", NULL, "NAME|INDEX", FLAG_KEY, "animation.name",
     "play a skinned mesh's animation (pelt info lists them): the fur follows and lags"},
    {"--wind", NULL, "X,Y,Z", FLAG_VEC3, "forces.wind", "wind (acceleration, world units/s^2)"},
    {"--gravity", NULL, "X,Y,Z", FLAG_VEC3, "forces.gravity", "gravity (default 0,-9.81,0)"},
    {"--curl-frequency", NULL, "W", FLAG_KEY, "fur.curl_frequency", "curl frequency omega (Silva Eq. 4)"},
    {"--curl-radius", NULL, "K", FLAG_KEY, "fur.curl_radius", "curl radius K_alpha in world units (Silva Eq. 4)"},
    {"--preset", NULL, "NAME", FLAG_KEY, "fur.preset", NULL, NULL}, /* help: the library's curl looks */
    {"--drops", NULL, "N", FLAG_KEY, "wetness.drops.count", "N random droplets at the start"},
    {"--rain", NULL, "RATE", FLAG_KEY, "wetness.rain.rate", "droplets per second"},
    {"--dry-rate", NULL, "R", FLAG_KEY, "wetness.dry_rate", "wetness lost per second"},
    {"--mask-image", NULL, "FILE", FLAG_KEY, "wetness.mask_image", "greyscale image painted as water"},
    {"--mask-out", NULL, "FILE", FLAG_MASK_OUT, NULL, "write the wetness mask as a PNG"},
    {"--fins", NULL, NULL, FLAG_SWITCH, "draw.fins=true",
     "draw the fins, textured quads on the edges near the silhouette (default)"},
    {"--no-fins", NULL, NULL, FLAG_SWITCH, "draw.fins=false",
     "no fins: the back-facing shells near the silhouette carry it"},
    {"--strands", NULL, NULL, FLAG_SWITCH, "render.mode=strands",
     "the strand reference: every hair as geometry in place of shells and fins (a still, seconds a frame)"},
    {"--strand-samples", NULL, "K", FLAG_KEY, "render.strand_samples",
     "the strand reference drawn at K x the size and averaged down (default 4)"},
    {"--fin-length", NULL, "X", FLAG_KEY, "fins.length",
     "fin hair height as a multiple of the fur length (default 1)"},
    {"--fin-density", NULL, "TEXELS", FLAG_KEY, "fins.density",
     "width of the slab of hair in the fin texture: denser fins (default texture size / 16)"},
    {"--high-quality", NULL, NULL, FLAG_SWITCH,
     "fur.layers=128 fur.texture_size=512 fur.lod_shell_pixels=0.01 fur.lod_mesh_error=0.1 fur.texture_taps=4 fur.edge_depth=16",
     "shells as close to the hairs as the look measures them (docs/reference.md): 128 layers, a 512 texture, "
     "every shell drawn, the full mesh, 4 fetches along a grazing footprint, edge-on shells as deep as the hairs; about 6x the frame and 4x the memory"},
    {"--inter-shadow", NULL, NULL, FLAG_SWITCH, "fur.inter_shadow=true",
     "Kenwright's inter-fur shadows: each hair shades the hair behind it from the light"},
    {"--shadows", NULL, NULL, FLAG_SWITCH, "shadows.enabled=true",
     "shadows from the light: deep opacity maps of the skin and the fur (docs/shadows.md)"},
    {"--no-shadows", NULL, NULL, FLAG_SWITCH, "shadows.enabled=false", "no shadows from the light (default)"},
    {"--ground", NULL, NULL, FLAG_SWITCH, "ground.enabled=true", "a ground plane under the mesh that receives shadows"},
    {"--shading", NULL, "MODEL", FLAG_KEY, "shading.model",
     "hair lighting: kajiya-kay (default), lengyel-table or marschner"},
    {"--groom", NULL, "FILE", FLAG_KEY, "fur.groom", "a groom file (PLY) to load (docs/grooming.md)"},
    {"--save-groom", NULL, "FILE", FLAG_GROOM_OUT, NULL,
     "write the groom (maps, vertex colours, groom file and strokes applied) as a PLY"},
    {"--drop-at", NULL, "X,Y,R", FLAG_DROP_AT, NULL,
     "a droplet where the ray through pixel (X, Y) hits, radius R in world units (repeatable)"},
    {"--set", NULL, "KEY=VALUE", FLAG_SET, NULL, "set any scene key (see docs/scene-format.md)"},
    {"--warmup", NULL, "N", FLAG_WARMUP, NULL, "bench: untimed frames first (default 5)"},
    {"--clumps", NULL, NULL, FLAG_CLUMPS, NULL,
     "bench: also time the scene with 50 clumps over a third of the surface"},
    {"--droplets", NULL, NULL, FLAG_DROPLETS, NULL,
     "bench: time 10,000 droplets into a 2048^2 mask against one whole-mask upload"},
    {"--brush", NULL, NULL, FLAG_BRUSH, NULL,
     "bench: time 200 comb strokes (radius 2% and 5% of the mesh diagonal) and their uploads"},
    {"--floor", NULL, NULL, FLAG_FLOOR, NULL,
     "bench: also time the frame with a one-fetch shell shader, with and without the fins, alternated (the floor)"},
    {"--plain", NULL, NULL, FLAG_PLAIN, NULL,
     "bench: also time a plain shell renderer in the same run (every shell along the normal, one fetch, blended, no fins)"},
    {"--lod-off", NULL, NULL, FLAG_LOD_OFF, NULL,
     "bench: also time the frame as fur.lod=off draws it (every shell over the full mesh, nothing culled), alternated"},
    {"--dolly", NULL, NULL, FLAG_DOLLY, NULL,
     "bench: time the frame as the camera backs away to 16x its distance (level of detail)"},
    {"--fur-px", NULL, "PX", FLAG_FUR_PX, NULL,
     "compare: how far the fur reaches past the skin's outline in pixels, for the stripe energy "
     "(default: where the strands cover half of the pixels at that distance)"},
    {"--quiet", "-q", NULL, FLAG_QUIET, NULL, "no progress output"},
};

#define FLAG_COUNT (sizeof flags / sizeof flags[0])

bool cli_scene_flag(size_t i, cli_flag_doc *out)
{
    if (i >= FLAG_COUNT) return false;
    const flag *f = &flags[i];
    *out = (cli_flag_doc){f->name, f->alias, f->metavar, f->help, f->values};
    if (f->key && strcmp(f->key, "fur.preset") == 0) {
        /* The curl looks' names come from the library's one list. */
        static char help[160], words[160];
        size_t h = 0, w = 0;
        for (int k = 0; pelt_curl_preset_names[k]; k++) {
            h += (size_t)snprintf(help + h, sizeof help - h, "%s%s", k ? ", " : "a curl look: ",
                                  pelt_curl_preset_names[k]);
            w += (size_t)snprintf(words + w, sizeof words - w, "%s%s", k ? " " : "", pelt_curl_preset_names[k]);
        }
        out->help = help;
        out->values = words;
    }
    return true;
}

static const flag *find_flag(const char *arg)
{
    for (size_t i = 0; i < FLAG_COUNT; i++)
        if (!strcmp(arg, flags[i].name) || (flags[i].alias && !strcmp(arg, flags[i].alias)))
            return &flags[i];
    return NULL;
}

static bool parse_uint(const char *s, unsigned long max, unsigned *out)
{
    char *end;
    errno = 0;
    if (!*s || *s == '-' || *s == '+') return false;
    unsigned long v = strtoul(s, &end, 10);
    if (errno || *end || v > max) return false;
    *out = (unsigned)v;
    return true;
}

static bool set_key(const char *cmd, const char *flag_name, pelt_scene *s, const char *key,
                    const char *value)
{
    pelt_error err = {0};
    if (pelt_scene_set(s, key, value, &err) != PELT_OK) {
        cli_error(cmd, "%s '%s': %s", flag_name, value, err.message);
        return false;
    }
    return true;
}

static bool apply(const char *cmd, const flag *f, const char *value, cli_options *o)
{
    char buf[2048];
    switch (f->kind) {
    case FLAG_KEY:
        return set_key(cmd, f->name, &o->scene, f->key, value);
    case FLAG_SWITCH: {
        /* One KEY=VALUE or several, space-separated, set in order. */
        for (const char *p = f->key; *p;) {
            size_t n = strcspn(p, " ");
            const char *eq = memchr(p, '=', n);
            char key[64], val[64];
            snprintf(key, sizeof key, "%.*s", (int)(eq - p), p);
            snprintf(val, sizeof val, "%.*s", (int)(p + n - eq - 1), eq + 1);
            if (!set_key(cmd, f->name, &o->scene, key, val)) return false;
            p += n + (p[n] == ' ');
        }
        return true;
    }
    case FLAG_VEC3: {
        /* Exactly three comma-separated numbers. */
        char *end;
        const char *p = value;
        float v[3];
        for (int i = 0; i < 3; i++) {
            errno = 0;
            v[i] = strtof(p, &end);
            if (end == p || errno || !isfinite(v[i]) || (i < 2 && *end != ',') || (i == 2 && *end)) {
                cli_error(cmd, "%s '%s': expected three numbers X,Y,Z", f->name, value);
                return false;
            }
            p = end + 1;
        }
        snprintf(buf, sizeof buf, "[%.9g,%.9g,%.9g]", (double)v[0], (double)v[1], (double)v[2]);
        return set_key(cmd, f->name, &o->scene, f->key, buf);
    }
    case FLAG_SIZE: {
        unsigned w, h;
        const char *x = strchr(value, 'x');
        if (!x || (size_t)(x - value) >= 16) {
            cli_error(cmd, "--size '%s': expected WIDTHxHEIGHT, like 800x600", value);
            return false;
        }
        char wbuf[16];
        memcpy(wbuf, value, (size_t)(x - value));
        wbuf[x - value] = '\0';
        if (!parse_uint(wbuf, 16384, &w) || !parse_uint(x + 1, 16384, &h) || w == 0 || h == 0) {
            cli_error(cmd, "--size '%s': width and height must be 1..16384", value);
            return false;
        }
        o->scene.output.width = w;
        o->scene.output.height = h;
        return true;
    }
    case FLAG_MESH:
        if (!strcmp(value, "torus") || !strcmp(value, "sphere") || !strcmp(value, "square"))
            return set_key(cmd, f->name, &o->scene, "mesh.shape", value);
        if (strlen(value) >= PELT_SCENE_PATH_MAX) {
            cli_error(cmd, "--mesh: path too long");
            return false;
        }
        return set_key(cmd, f->name, &o->scene, "mesh.file", value) &&
               set_key(cmd, f->name, &o->scene, "mesh.shape", "file");
    case FLAG_SET: {
        const char *eq = strchr(value, '=');
        if (!eq || eq == value || (size_t)(eq - value) >= 256) {
            cli_error(cmd, "--set '%s': expected KEY=VALUE, like fur.layers=32", value);
            return false;
        }
        char key[256];
        memcpy(key, value, (size_t)(eq - value));
        key[eq - value] = '\0';
        return set_key(cmd, f->name, &o->scene, key, eq + 1);
    }
    case FLAG_OUTPUT:
        o->output = value;
        o->output_set = true;
        return true;
    case FLAG_MASK_OUT:
        o->mask_out = value;
        return true;
    case FLAG_GROOM_OUT:
        o->groom_out = value;
        return true;
    case FLAG_WARMUP:
        if (!parse_uint(value, 100000, &o->warmup)) {
            cli_error(cmd, "--warmup '%s': expected a whole number 0..100000", value);
            return false;
        }
        return true;
    case FLAG_DROP_AT: {
        float v[3];
        char *end;
        const char *p = value;
        for (int i = 0; i < 3; i++) {
            errno = 0;
            v[i] = strtof(p, &end);
            if (end == p || errno || !isfinite(v[i]) || (i < 2 && *end != ',') || (i == 2 && *end)) {
                cli_error(cmd, "--drop-at '%s': expected X,Y,R (pixel column, row, world radius)", value);
                return false;
            }
            p = end + 1;
        }
        if (!(v[2] > 0.0f) || o->drop_count >= CLI_MAX_DROPS) {
            cli_error(cmd, "--drop-at '%s': the radius must be positive, at most %d drops", value,
                      CLI_MAX_DROPS);
            return false;
        }
        memcpy(o->drops[o->drop_count++], v, sizeof v);
        return true;
    }
    case FLAG_CLUMPS:
        o->bench_clumps = true;
        return true;
    case FLAG_BRUSH:
        o->bench_brush = true;
        return true;
    case FLAG_FLOOR:
        o->bench_floor = true;
        return true;
    case FLAG_PLAIN:
        o->bench_plain = true;
        return true;
    case FLAG_DOLLY:
        o->bench_dolly = true;
        return true;
    case FLAG_LOD_OFF:
        o->bench_lod_off = true;
        return true;
    case FLAG_DROPLETS:
        o->bench_droplets = true;
        return true;
    case FLAG_FUR_PX: {
        char *end;
        errno = 0;
        float v = strtof(value, &end);
        if (end == value || *end || errno || !isfinite(v) || !(v > 0.0f) || v > 4096.0f) {
            cli_error(cmd, "--fur-px '%s': expected a number of pixels in (0, 4096]", value);
            return false;
        }
        o->fur_px = v;
        return true;
    }
    case FLAG_QUIET:
        o->quiet = true;
        return true;
    }
    return false;
}

int cli_parse_command(const char *cmd, int argc, char **argv, cli_options *o)
{
    int rc = cli_parse(cmd, argc, argv, o);
    if (rc == 0) return -1;
    cli_options_free(o);
    return rc == 1 ? 0 : rc;
}

int cli_parse(const char *cmd, int argc, char **argv, cli_options *o)
{
    memset(o, 0, sizeof *o);
    pelt_scene_defaults(&o->scene);
    o->output = "pelt.png";
    o->warmup = 5;
    int i = 0;
    for (int k = 0; k < argc; k++)
        if (!strcmp(argv[k], "-h") || !strcmp(argv[k], "--help")) {
            cli_print_help(stdout, cli_find_command(cmd));
            return 1;
        }
    /* An optional scene file comes first. */
    if (argc > 0 && argv[0][0] != '-') {
        pelt_error err = {0};
        if (pelt_scene_load(argv[0], &o->scene, &err) != PELT_OK) {
            cli_error(cmd, "%s", err.message);
            return 2;
        }
        i = 1;
    }
    for (; i < argc; i++) {
        const flag *f = find_flag(argv[i]);
        if (!f) {
            if (argv[i][0] != '-')
                cli_error(cmd, "unexpected argument '%s' (the scene file must come first)", argv[i]);
            else
                cli_error(cmd, "unknown flag '%s' (see pelt %s --help)", argv[i], cmd);
            return 2;
        }
        const char *value = NULL;
        if (f->metavar) {
            if (i + 1 >= argc) {
                cli_error(cmd, "%s needs a value (%s)", f->name, f->metavar);
                return 2;
            }
            value = argv[++i];
        }
        if (!apply(cmd, f, value, o)) return 2;
    }
    return 0;
}

void cli_options_free(cli_options *o) { pelt_scene_free(&o->scene); }

bool cli_frame_path(const char *pattern, unsigned frame, char *out, size_t out_size)
{
    const char *pc = strchr(pattern, '%');
    if (!pc) {
        int n = snprintf(out, out_size, "%s", pattern);
        return n >= 0 && (size_t)n < out_size;
    }
    /* One conversion: %d or %0Nd with N <= 9; nothing else may use '%'. */
    const char *q = pc + 1;
    int width = 0;
    if (*q == '0') {
        q++;
        if (*q < '1' || *q > '9') return false;
        width = *q++ - '0';
    }
    if (*q != 'd' || strchr(q + 1, '%')) return false;
    int n = snprintf(out, out_size, "%.*s%0*u%s", (int)(pc - pattern), pattern, width, frame, q + 1);
    return n >= 0 && (size_t)n < out_size;
}
