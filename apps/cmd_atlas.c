/* pelt atlas: build a mesh's surface atlas (Lengyel et al. §2.1 patches,
 * §3 direction field) and draw it to PNG for inspection. */
#include "apps/cli.h"
#include "pelt/atlas.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const CMD = "atlas";

static const cli_flag_doc atlas_flags[] = {
    {"-o", NULL, "FILE", "output PNG (default atlas.png)", NULL},
    {"--size", NULL, "N", "image side in pixels (default 1024)", NULL},
    {"--mode", NULL, "M", "auto | mesh-uvs | patches (default auto)", "auto mesh-uvs patches"},
    {"--direction", NULL, "X,Y,Z", "global hair direction (default 0,-1,0: combed down)", NULL},
    {"--density", NULL, "D", "fur-texture tiles per world unit (default 8 / bbox diagonal)", NULL},
    {"--mask-size", NULL, "N", "atlas side in texels (default from the triangle count)", NULL},
    {"--seed", NULL, "S", "patch seeds and colours (default 0)", NULL},
    {"--no-cache", NULL, NULL, "always rebuild, never read or write the cache", NULL},
    {"--cache-dir", NULL, "DIR", "cache directory (default $XDG_CACHE_HOME/pelt or ~/.cache/pelt)",
     NULL},
};
#define ATLAS_FLAG_COUNT (sizeof atlas_flags / sizeof atlas_flags[0])

bool cli_atlas_flag(size_t i, cli_flag_doc *out)
{
    if (i >= ATLAS_FLAG_COUNT) return false;
    *out = atlas_flags[i];
    return true;
}

static bool parse_uint(const char *s, unsigned long lo, unsigned long hi, unsigned *out)
{
    char *end;
    if (!*s || *s == '-' || *s == '+') return false;
    errno = 0;
    unsigned long v = strtoul(s, &end, 10);
    if (errno || *end || v < lo || v > hi) return false;
    *out = (unsigned)v;
    return true;
}

static bool parse_vec3(const char *s, float v[3])
{
    const char *p = s;
    for (int i = 0; i < 3; i++) {
        char *end;
        errno = 0;
        v[i] = strtof(p, &end);
        if (end == p || errno || !isfinite(v[i])) return false;
        if (i < 2 ? *end != ',' : *end != '\0') return false;
        p = end + 1;
    }
    return true;
}

static pelt_status load_shape(const char *name, pelt_mesh **m, pelt_error *err)
{
    if (!strcmp(name, "torus")) return pelt_mesh_torus(1.0f, 0.4f, 78, 60, m, err);
    if (!strcmp(name, "sphere")) return pelt_mesh_sphere(1.0f, 64, 32, m, err);
    if (!strcmp(name, "square")) return pelt_mesh_square(2.0f, 16, m, err);
    return pelt_mesh_load(name, m, err);
}

/* pelt_atlas_draw puts v = 0 in row 0; PNG rows run top first, so flip to
 * show v upwards as uv editors do. */
static void flip_rows(uint8_t *rgba, unsigned w, unsigned h)
{
    size_t stride = (size_t)w * 4;
    for (unsigned y = 0; y < h / 2; y++) {
        uint8_t *a = rgba + (size_t)y * stride, *b = rgba + (size_t)(h - 1 - y) * stride;
        for (size_t i = 0; i < stride; i++) {
            uint8_t t = a[i];
            a[i] = b[i];
            b[i] = t;
        }
    }
}

static const char *mode_name(int mode)
{
    return mode == PELT_ATLAS_MESH_UVS ? "mesh uvs" : "patches";
}

static void print_warning(pelt_log_level level, const char *message, void *user)
{
    (void)user;
    if (level <= PELT_LOG_WARNING)
        fprintf(stderr, "pelt %s: %s%s\n", CMD, level == PELT_LOG_WARNING ? "warning: " : "", message);
}

int cmd_atlas(int argc, char **argv)
{
    const char *mesh_arg = NULL, *output = "atlas.png", *cache_dir = NULL;
    unsigned size = 1024;
    bool no_cache = false;
    pelt_atlas_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.hooks.logger.func = print_warning; /* a damaged cache file, unusable uvs */

    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            cli_print_help(stdout, cli_find_command(CMD));
            return 0;
        }
        if (!strcmp(a, "--no-cache")) {
            no_cache = true;
            continue;
        }
        if (a[0] == '-' && a[1] != '\0') {
            bool known = false; /* a flag of the table that takes a value */
            for (size_t k = 0; k < ATLAS_FLAG_COUNT; k++)
                if (!strcmp(a, atlas_flags[k].name) && atlas_flags[k].metavar) known = true;
            if (!known) {
                cli_error(CMD, "unknown flag '%s' (see pelt atlas --help)", a);
                return 2;
            }
            if (i + 1 >= argc) {
                cli_error(CMD, "%s needs a value", a);
                return 2;
            }
            const char *v = argv[++i];
            bool ok = true;
            const char *expect = "";
            if (!strcmp(a, "-o")) {
                ok = *v != '\0';
                output = v;
                expect = "a file name";
            } else if (!strcmp(a, "--size")) {
                ok = parse_uint(v, 1, 16384, &size);
                expect = "an integer in [1, 16384]";
            } else if (!strcmp(a, "--mode")) {
                expect = "auto, mesh-uvs or patches";
                if (!strcmp(v, "auto")) desc.mode = PELT_ATLAS_AUTO;
                else if (!strcmp(v, "mesh-uvs")) desc.mode = PELT_ATLAS_MESH_UVS;
                else if (!strcmp(v, "patches")) desc.mode = PELT_ATLAS_PATCHES;
                else ok = false;
            } else if (!strcmp(a, "--direction")) {
                ok = parse_vec3(v, desc.direction);
                expect = "three numbers X,Y,Z";
            } else if (!strcmp(a, "--density")) {
                char *end;
                errno = 0;
                desc.texel_density = strtof(v, &end);
                ok = end != v && !*end && !errno && isfinite(desc.texel_density) &&
                     desc.texel_density > 0.0f;
                expect = "a number > 0";
            } else if (!strcmp(a, "--mask-size")) {
                ok = parse_uint(v, 1, 4096, &desc.mask_size);
                expect = "an integer in [1, 4096]";
            } else if (!strcmp(a, "--seed")) {
                unsigned seed = 0;
                ok = parse_uint(v, 0, UINT32_MAX, &seed);
                desc.seed = seed;
                expect = "an integer in [0, 4294967295]";
            } else { /* --cache-dir */
                ok = *v != '\0';
                cache_dir = v;
                expect = "a directory";
            }
            if (!ok) {
                cli_error(CMD, "%s '%s': expected %s", a, v, expect);
                return 2;
            }
            continue;
        }
        if (mesh_arg) {
            cli_error(CMD, "unexpected argument '%s': one mesh only (see pelt atlas --help)", a);
            return 2;
        }
        mesh_arg = a;
    }
    if (!mesh_arg) {
        cli_error(CMD, "expected a mesh file or torus / sphere / square (see pelt atlas --help)");
        return 2;
    }

    char default_dir[1024];
    if (no_cache)
        desc.cache_dir = NULL;
    else if (cache_dir)
        desc.cache_dir = cache_dir;
    else if (pelt_atlas_default_cache_dir(default_dir, sizeof default_dir))
        desc.cache_dir = default_dir;

    pelt_error err = {0};
    pelt_mesh *mesh = NULL;
    if (load_shape(mesh_arg, &mesh, &err) != PELT_OK) {
        cli_error(CMD, "%s", err.message);
        return 1;
    }
    pelt_atlas *atlas = NULL;
    if (pelt_atlas_create(mesh, &desc, &atlas, &err) != PELT_OK) {
        cli_error(CMD, "%s: %s", mesh_arg, err.message);
        pelt_mesh_destroy(mesh);
        return 1;
    }
    pelt_mesh_destroy(mesh);

    int rc = 1;
    uint8_t *rgba = malloc((size_t)size * size * 4); /* size <= 16384: no overflow */
    if (!rgba) {
        cli_error(CMD, "out of memory for a %ux%u image", size, size);
        goto done;
    }
    if (pelt_atlas_draw(atlas, rgba, size, size, desc.seed, &err) != PELT_OK) {
        cli_error(CMD, "%s", err.message);
        goto done;
    }
    flip_rows(rgba, size, size);
    if (!cli_write_png(CMD, output, rgba, size, size)) goto done;

    const pelt_atlas_stats *s = pelt_atlas_get_stats(atlas);
    /* A build logged it already; a cache hit did not. */
    if (s->uv_warning[0] && s->from_cache) fprintf(stderr, "pelt atlas: warning: %s\n", s->uv_warning);
    printf("%s\n"
           "  mode        %s\n"
           "  triangles   %zu\n"
           "  vertices    %zu (after splitting)\n"
           "  patches     %zu\n"
           "  mask size   %u\n"
           "  density     %g fur tiles per unit\n"
           "  stretch     %.3f / %.3f / %.3f (min / mean / max)\n"
           "  flipped     %zu\n"
           "  fill        %.3f\n"
           "  build       %.3f s\n"
           "  cache       %s%s%s\n"
           "  image       %s (%ux%u)\n",
           mesh_arg, mode_name(s->mode_used), s->triangle_count, s->vertex_count, s->patch_count,
           s->mask_size, (double)s->texel_density, (double)s->stretch_min,
           (double)s->stretch_mean, (double)s->stretch_max, s->flipped, (double)s->fill,
           s->build_seconds,
           s->from_cache ? "hit: loaded from the cache"
           : desc.cache_dir ? "miss: built, stored"
                            : "off",
           desc.cache_dir ? " in " : "", desc.cache_dir ? desc.cache_dir : "",
           output, size, size);
    rc = 0;
done:
    free(rgba);
    pelt_atlas_destroy(atlas);
    return rc;
}
