/* Scene files: defaults, every field, every error path, --set overrides,
 * wind keyframes, the animated model matrix and the shipped scenes. */
#define _POSIX_C_SOURCE 200809L
#include "pelt/scene.h"
#include "pelt/params.h"

#include "support/check.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCENES PELT_TEST_DATA "/scenes/"
#define SHIPPED PELT_TEST_DATA "/../../scenes/"

static bool contains(const char *haystack, const char *needle)
{
    bool ok = strstr(haystack, needle) != NULL;
    if (!ok) fprintf(stderr, "  message \"%s\" lacks \"%s\"\n", haystack, needle);
    return ok;
}

/* A scene that owns nothing and equals the defaults, field by field. */
static bool is_default(const pelt_scene *s)
{
    pelt_scene d;
    pelt_scene_defaults(&d);
    return memcmp(&d, s, sizeof d) == 0;
}

static void defaults_equal_table1(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    CHECK(s.mesh.shape == PELT_SHAPE_TORUS);
    CHECK(s.mesh.major_segments == 78);
    CHECK(s.mesh.minor_segments == 60);
    /* two triangles per quad of the torus grid: Silva Table 1's 9,360 */
    CHECK(2u * s.mesh.major_segments * s.mesh.minor_segments == 9360u);
    CHECK_NEAR(s.mesh.major_radius, 1.0, 0);
    CHECK_NEAR(s.mesh.minor_radius, 0.4, 1e-7);
    CHECK_NEAR(s.mesh.scale, 1.0, 0);
    /* The fur desc stays zero: the library's rows are the one home of
       its defaults (test_scene_instance checks what they become). */
    size_t rows = 0;
    const pelt_param *p = pelt_fur_params(&rows);
    for (size_t i = 0; i < rows; i++) {
        const unsigned char *f = (const unsigned char *)&s.fur + p[i].offset;
        size_t bytes = p[i].type == PELT_PARAM_FLOAT ? p[i].count * sizeof(float)
                       : p[i].type == PELT_PARAM_BOOL ? sizeof(bool) : sizeof(unsigned);
        for (size_t b = 0; b < bytes; b++) CHECK(f[b] == 0);
    }
    CHECK(s.output.width == 800 && s.output.height == 600);
    CHECK(s.output.msaa == 4);
    CHECK(s.draw.exposure == 1.0f && s.draw.tone == PELT_TONE_FILMIC);
    CHECK(s.fur.wet.mask_size == 0); /* 0: the atlas picks, else 256 */
    CHECK(s.wetness.droplets == NULL && s.wetness.droplet_count == 0);
    CHECK(s.animation.wind_keys == NULL && s.animation.wind_key_count == 0);
    CHECK(s.animation.frames == 1);
    CHECK_NEAR(s.animation.fps, 30, 0);
    CHECK(s.fur_preset[0] == '\0');
    CHECK(s.texture.pattern == PELT_COLOR_PATTERN_NONE && s.texture.image[0] == '\0');
    CHECK(s.atlas.mode == PELT_ATLAS_AUTO);
}

static void defaults_camera_light_forces(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    CHECK_NEAR(s.camera.yaw, 30, 0);
    CHECK_NEAR(s.camera.pitch, 25, 0);
    CHECK_NEAR(s.camera.distance, 4.2, 1e-6);
    CHECK_NEAR(s.camera.fov_y, 40, 0);
    CHECK(s.camera.target[0] == 0 && s.camera.target[1] == 0 && s.camera.target[2] == 0);
    CHECK_NEAR(s.light.direction[0], 0.5, 0);
    CHECK_NEAR(s.light.direction[1], 1.0, 0);
    CHECK_NEAR(s.light.direction[2], 0.8, 1e-7);
    CHECK_NEAR(s.light.ambient, 0.25, 0);
    CHECK_NEAR(s.forces.gravity[1], -9.81, 1e-6);
    CHECK(s.forces.gravity[0] == 0 && s.forces.gravity[2] == 0);
    CHECK(s.forces.wind[0] == 0 && s.forces.wind[1] == 0 && s.forces.wind[2] == 0);
    CHECK_NEAR(s.forces.gust_strength, 0.5, 0);
    CHECK_NEAR(s.forces.gust_scale, 0.5, 0);
    CHECK_NEAR(s.forces.gust_frequency, 1.5, 0);
}

static void empty_object_gives_defaults(void)
{
    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_parse("{}", "x.json", &s, &err) == PELT_OK);
    CHECK(is_default(&s));
    pelt_scene_free(&s);
}

static void full_scene_sets_every_field(void)
{
    pelt_scene s;
    pelt_error err = {0};
    pelt_status st = pelt_scene_load(SCENES "full.json", &s, &err);
    CHECK(st == PELT_OK);
    if (st != PELT_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return;
    }
    CHECK(s.mesh.shape == PELT_SHAPE_SPHERE);
    CHECK_NEAR(s.mesh.major_radius, 2.0, 0);
    CHECK_NEAR(s.mesh.minor_radius, 0.5, 0);
    CHECK(s.mesh.major_segments == 40 && s.mesh.minor_segments == 20);
    CHECK_NEAR(s.mesh.radius, 1.5, 0);
    CHECK(s.mesh.slices == 48 && s.mesh.stacks == 24);
    CHECK_NEAR(s.mesh.size, 3.0, 0);
    CHECK(s.mesh.subdivisions == 8);
    CHECK_NEAR(s.mesh.rotation[0], 90, 0);
    CHECK_NEAR(s.mesh.rotation[1], 45, 0);
    CHECK_NEAR(s.mesh.rotation[2], -30, 0);
    CHECK_NEAR(s.mesh.scale, 2.5, 0);

    CHECK(strcmp(s.fur_preset, "many-small-curls") == 0 || strcmp(s.fur_preset, "small_curls") == 0);
    CHECK(s.fur.layers == 32);
    CHECK_NEAR(s.fur.layers_per_turn, 8, 0);
    CHECK_NEAR(s.fur.length, 0.05, 1e-7);
    CHECK(s.fur.look.texture_size == 128);
    CHECK(s.fur.seed == 4000000000u);
    CHECK_NEAR(s.fur.look.density, 2000, 0);
    CHECK_NEAR(s.fur.look.strand_radius, 1.2, 1e-6);
    CHECK_NEAR(s.fur.look.taper, 0.5, 0);
    CHECK_NEAR(s.fur.look.strand_curl, 3.5, 0);
    CHECK_NEAR(s.fur.look.strand_curl_turns, 4, 0);
    CHECK(s.fur.look.strand_curl_shape == PELT_STRAND_CURL_WAVE);
    CHECK_NEAR(s.fur.look.tiling, 4, 0);
    CHECK_NEAR(s.fur.look.color[0], 0.3, 1e-7);
    CHECK_NEAR(s.fur.look.tip_color[2], 0.4, 1e-7);
    CHECK_NEAR(s.fur.look.specular[1], 0.2, 1e-7);
    CHECK_NEAR(s.fur.look.shininess, 60, 0);
    CHECK_NEAR(s.fur.look.shadow, 3, 0);
    CHECK_NEAR(s.fur.look.curl_frequency, 12.5, 0);
    CHECK_NEAR(s.fur.look.curl_radius, 0.01, 1e-8);

    CHECK(s.texture.pattern == PELT_COLOR_PATTERN_STRIPES);
    CHECK(s.texture.image[0] == '\0');
    CHECK_NEAR(s.fur.look.color_scale, 3, 0);

    CHECK_NEAR(s.camera.yaw, -45, 0);
    CHECK_NEAR(s.camera.pitch, 10, 0);
    CHECK_NEAR(s.camera.distance, 6, 0);
    CHECK_NEAR(s.camera.fov_y, 50, 0);
    CHECK_NEAR(s.camera.target[1], 0.5, 0);
    CHECK_NEAR(s.light.direction[0], 0, 0);
    CHECK_NEAR(s.light.color[2], 0.8, 1e-7);
    CHECK_NEAR(s.light.ambient, 0.1, 1e-7);

    CHECK(s.output.width == 320 && s.output.height == 240 && s.output.msaa == 2);
    /* three numbers: alpha stays opaque */
    CHECK_NEAR(s.output.background[0], 1, 0);
    CHECK_NEAR(s.output.background[3], 1, 0);
    CHECK_NEAR(s.draw.exposure, 1.5, 0);
    CHECK(s.draw.tone == PELT_TONE_NONE);

    CHECK_NEAR(s.forces.gravity[1], -5, 0);
    CHECK_NEAR(s.forces.wind[0], 2, 0);
    CHECK_NEAR(s.forces.gust_strength, 0.2, 1e-7);
    CHECK_NEAR(s.forces.gust_scale, 1.5, 0);
    CHECK_NEAR(s.forces.gust_frequency, 3, 0);
    CHECK_NEAR(s.fur.dynamics.spring_k, 200, 0);
    CHECK_NEAR(s.fur.dynamics.mass, 0.5, 0);
    CHECK_NEAR(s.fur.dynamics.damping, 4, 0);

    CHECK(s.animation.frames == 90);
    CHECK_NEAR(s.animation.fps, 24, 0);
    CHECK_NEAR(s.animation.turntable, 45, 0);
    CHECK_NEAR(s.animation.shake_amplitude, 0.1, 1e-7);
    CHECK_NEAR(s.animation.shake_frequency, 3, 0);
    CHECK_NEAR(s.animation.bounce_height, 0.2, 1e-7);
    CHECK_NEAR(s.animation.bounce_frequency, 0.5, 0);
    CHECK(s.animation.wind_key_count == 3);
    if (s.animation.wind_key_count == 3) {
        CHECK_NEAR(s.animation.wind_keys[1].time, 2, 0);
        CHECK_NEAR(s.animation.wind_keys[2].wind[1], 2, 0);
    }

    CHECK(s.fur.wet.mask_size == 512);
    CHECK(s.wetness.droplet_count == 3);
    if (s.wetness.droplet_count == 3) {
        CHECK_NEAR(s.wetness.droplets[0].center[0], 0.25, 0);
        CHECK_NEAR(s.wetness.droplets[0].wetness, 0.8, 1e-7);
        /* wetness omitted: a full drop */
        CHECK_NEAR(s.wetness.droplets[1].wetness, 1.0, 0);
        CHECK_NEAR(s.wetness.droplets[1].radius, 0.1, 1e-7);
        CHECK_NEAR(s.wetness.droplets[2].wetness, -1.0, 0);
    }
    CHECK(s.wetness.drops == 50 && s.wetness.drops_seed == 7);
    CHECK_NEAR(s.wetness.drops_radius[0], 0.01, 1e-8);
    CHECK_NEAR(s.wetness.drops_radius[1], 0.03, 1e-8);
    CHECK_NEAR(s.wetness.drops_wetness[0], 0.5, 0);
    CHECK_NEAR(s.wetness.drops_wetness[1], 0.9, 1e-7);
    CHECK_NEAR(s.wetness.rain.rate, 20, 0);
    CHECK_NEAR(s.wetness.rain.radius_min, 0.02, 1e-8);
    CHECK_NEAR(s.wetness.rain.radius_max, 0.04, 1e-8);
    CHECK_NEAR(s.wetness.rain.wetness_min, 0.7, 1e-7);
    CHECK_NEAR(s.wetness.rain.wetness_max, 1.0, 0);
    CHECK(s.wetness.rain.seed == 9);
    CHECK_NEAR(s.wetness.rain_start, 1, 0);
    CHECK_NEAR(s.wetness.rain_stop, 4, 0);
    CHECK_NEAR(s.wetness.dry_rate, 0.1, 1e-7);
    CHECK_NEAR(s.fur.wet.clump_blend, 0.25, 0);
    CHECK_NEAR(s.fur.wet.clump_tightness, 0.75, 0);
    CHECK_NEAR(s.fur.wet.darken, 0.5, 0);
    CHECK_NEAR(s.fur.wet.clump_size, 0.04, 1e-8);
    CHECK_NEAR(s.fur.wet.gloss, 3, 0);
    CHECK_NEAR(s.fur.wet.gloss_sharpness, 6, 0);
    CHECK(strcmp(s.wetness.mask_image, SCENES "word.png") == 0);
    CHECK_NEAR(s.wetness.mask_image_wetness, 0.8, 1e-7);

    CHECK(s.atlas.mode == PELT_ATLAS_PATCHES);
    CHECK_NEAR(s.atlas.texel_density, 8, 0);
    CHECK_NEAR(s.atlas.direction[0], 1, 0);
    CHECK_NEAR(s.atlas.direction[1], 0, 0);
    CHECK_NEAR(s.atlas.max_stretch, 3, 0);
    pelt_scene_free(&s);
    CHECK(s.wetness.droplets == NULL && s.animation.wind_keys == NULL);
}

static void relative_paths_resolve_against_scene_dir(void)
{
    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_load(SCENES "mesh_file.json", &s, &err) == PELT_OK);
    /* "mesh": "..." is short for {"file": "..."} and selects the file shape */
    CHECK(s.mesh.shape == PELT_SHAPE_FILE);
    CHECK(strcmp(s.mesh.file, SCENES "meshes/bunny.off") == 0);
    CHECK(strcmp(s.texture.image, SCENES "../fur.png") == 0);
    pelt_scene_free(&s);

    CHECK(pelt_scene_load(SCENES "sub/abs.json", &s, &err) == PELT_OK);
    CHECK(strcmp(s.mesh.file, "/usr/share/meshes/cow.off") == 0);
    CHECK_NEAR(s.mesh.scale, 0.5, 0);
    pelt_scene_free(&s);

    /* a name without a directory leaves relative paths as they are */
    CHECK(pelt_scene_parse("{\"mesh\": {\"file\": \"a.obj\"}}", "s.json", &s, &err) == PELT_OK);
    CHECK(strcmp(s.mesh.file, "a.obj") == 0);
    pelt_scene_free(&s);
}

/* One bad scene text: the status, and words the message must hold. */
typedef struct bad_case {
    const char *json;
    pelt_status status;
    const char *words[3];
} bad_case;

static void each_bad_value_names_file_and_key(void)
{
    static const bad_case cases[] = {
        {"{\"fur\": {\"layers\": -3}}", PELT_ERR_FORMAT, {"fur.layers", "-3", NULL}},
        {"{\"fur\": {\"layers\": 300}}", PELT_ERR_FORMAT, {"fur.layers", "from 1 to 256"}},
        /* The library's range (pelt/params.h), not a second one. */
        {"{\"fur\": {\"texture_size\": 8192}}", PELT_ERR_FORMAT, {"fur.texture_size", "from 8 to 4096"}},
        {"{\"fur\": {\"texture_size\": 4}}", PELT_ERR_FORMAT, {"fur.texture_size", "got 4"}},
        {"{\"wetness\": {\"darken\": 1}}", PELT_ERR_FORMAT, {"wetness.darken", "[0, 1)"}},
        {"{\"fur\": {\"layers\": 257}}", PELT_ERR_FORMAT, {"fur.layers", "257"}},
        {"{\"fur\": {\"layers\": 2.5}}", PELT_ERR_FORMAT, {"fur.layers", "2.5"}},
        {"{\"fur\": {\"layers\": \"16\"}}", PELT_ERR_FORMAT, {"fur.layers", "\"16\""}},
        {"{\"fur\": {\"layers\": null}}", PELT_ERR_FORMAT, {"fur.layers", "null"}},
        {"{\"fur\": {\"seed\": -1}}", PELT_ERR_FORMAT, {"fur.seed"}},
        {"{\"fur\": {\"seed\": 4294967296}}", PELT_ERR_FORMAT, {"fur.seed"}},
        {"{\"fur\": {\"taper\": 1.5}}", PELT_ERR_FORMAT, {"fur.taper", "1.5"}},
        {"{\"fur\": {\"strand_curl\": 65}}", PELT_ERR_FORMAT, {"fur.strand_curl", "65"}},
        {"{\"fur\": {\"strand_curl_turns\": -1}}", PELT_ERR_FORMAT, {"fur.strand_curl_turns", "-1"}},
        {"{\"fur\": {\"strand_curl_shape\": \"spiral\"}}", PELT_ERR_FORMAT,
         {"fur.strand_curl_shape", "\"spiral\"", "helix"}},
        {"{\"fur\": {\"shadow\": 0.5}}", PELT_ERR_FORMAT, {"fur.shadow", "0.5"}},
        {"{\"fur\": {\"color\": [1, 0]}}", PELT_ERR_FORMAT, {"fur.color", "3 numbers"}},
        {"{\"fur\": {\"color\": [1, 0, 2]}}", PELT_ERR_FORMAT, {"fur.color[2]", "2"}},
        {"{\"fur\": {\"color\": [1, true, 0]}}", PELT_ERR_FORMAT, {"fur.color[1]", "true"}},
        {"{\"fur\": {\"preset\": \"curly\"}}", PELT_ERR_FORMAT, {"fur.preset", "wavy", "curly"}},
        {"{\"fur\": 16}", PELT_ERR_FORMAT, {"fur: expected an object", "16"}},
        {"{\"fur\": {\"lenght\": 0.02}}", PELT_ERR_FORMAT, {"'fur.lenght'", "'fur.length'"}},
        {"{\"camra\": {}}", PELT_ERR_FORMAT, {"'camra'", "'camera'"}},
        {"{\"zzzzzzzz\": 1}", PELT_ERR_FORMAT, {"unknown key 'zzzzzzzz'"}},
        {"{\"fur\": {\"length_range\": [2, 1]}}", PELT_ERR_FORMAT, {"fur.length_range", "min <= max"}},
        {"{\"fur\": {\"vertex_colors\": \"paint\"}}", PELT_ERR_FORMAT, {"fur.vertex_colors", "hair"}},
        {"{\"strokes\": [{\"tool\": \"comb\", \"radius\": 0, \"at\": [0, 0, 0]}]}", PELT_ERR_FORMAT,
         {"strokes[0].radius", "positive"}},
        {"{\"strokes\": [{\"radius\": 1, \"at\": [0, 0, 0]}]}", PELT_ERR_FORMAT, {"strokes[0]", "'tool'"}},
        {"{\"strokes\": [{\"tool\": \"color\", \"radius\": 1, \"pixel\": [1, 2], \"at\": [0, 0, 0]}]}",
         PELT_ERR_FORMAT, {"strokes[0]", "not both"}},
        {"{\"strokes\": {\"tool\": \"comb\"}}", PELT_ERR_FORMAT, {"strokes", "an array"}},
        {"{\"fur\": {\"layers\": 8, \"layers\": 9}}", PELT_ERR_FORMAT, {"duplicate", "fur.layers"}},
        {"{\"camera\": {\"distance\": 1e999}}", PELT_ERR_FORMAT, {"camera.distance"}},
        {"{\"wetness\": {\"gloss\": 0.5}}", PELT_ERR_FORMAT, {"wetness.gloss", "0.5", "[1, 16]"}},
        {"{\"wetness\": {\"clump_size\": -0.1}}", PELT_ERR_FORMAT, {"wetness.clump_size", "-0.1"}},
        {"{\"wetness\": {\"gloss_sharpness\": 65}}", PELT_ERR_FORMAT, {"wetness.gloss_sharpness", "65"}},
        {"{\"camera\": {\"distance\": 0}}", PELT_ERR_FORMAT, {"camera.distance", "positive"}},
        {"{\"camera\": {\"pitch\": 90}}", PELT_ERR_FORMAT, {"camera.pitch"}},
        {"{\"camera\": {\"target\": [0, 1]}}", PELT_ERR_FORMAT, {"camera.target", "an array of 2"}},
        {"{\"light\": {\"direction\": [0, 0, 0]}}", PELT_ERR_FORMAT, {"light.direction", "non-zero"}},
        {"{\"output\": {\"width\": 16385}}", PELT_ERR_FORMAT, {"output.width", "16385"}},
        {"{\"output\": {\"height\": 0}}", PELT_ERR_FORMAT, {"output.height"}},
        {"{\"output\": {\"background\": [0, 0]}}", PELT_ERR_FORMAT, {"output.background"}},
        {"{\"output\": {\"exposure\": 0}}", PELT_ERR_FORMAT, {"output.exposure", "0.01"}},
        {"{\"output\": {\"tone\": \"aces\"}}", PELT_ERR_FORMAT, {"output.tone", "\"aces\"", "filmic"}},
        {"{\"mesh\": {\"shape\": \"cube\"}}", PELT_ERR_FORMAT, {"mesh.shape", "\"cube\"", "torus"}},
        {"{\"mesh\": {\"shape\": \"file\"}}", PELT_ERR_FORMAT, {"mesh.file"}},
        {"{\"mesh\": {\"file\": \"a.obj\", \"shape\": \"torus\"}}", PELT_ERR_FORMAT,
         {"mesh", "not both"}},
        {"{\"mesh\": {\"scale\": -1}}", PELT_ERR_FORMAT, {"mesh.scale"}},
        {"{\"mesh\": {\"file\": 3}}", PELT_ERR_FORMAT, {"mesh.file", "path"}},
        {"{\"texture\": {\"pattern\": \"dots\"}}", PELT_ERR_FORMAT, {"texture.pattern", "spots"}},
        {"{\"texture\": {\"image\": \"a.png\", \"pattern\": \"noise\"}}", PELT_ERR_FORMAT,
         {"texture", "not both"}},
        {"{\"animation\": {\"fps\": 0}}", PELT_ERR_FORMAT, {"animation.fps"}},
        {"{\"animation\": {\"shake\": {\"amplitud\": 1}}}", PELT_ERR_FORMAT,
         {"'animation.shake.amplitud'", "'animation.shake.amplitude'"}},
        {"{\"animation\": {\"wind\": [{\"time\": 1, \"wind\": [0,0,0]},"
         " {\"time\": 1, \"wind\": [1,0,0]}]}}",
         PELT_ERR_FORMAT, {"animation.wind[1].time", "increasing"}},
        {"{\"animation\": {\"wind\": [{\"time\": 1}]}}", PELT_ERR_FORMAT,
         {"animation.wind[0]", "'wind'"}},
        {"{\"animation\": {\"wind\": {}}}", PELT_ERR_FORMAT, {"animation.wind", "array"}},
        {"{\"wetness\": {\"droplets\": [{\"center\": [0.5, 0.5]}]}}", PELT_ERR_FORMAT,
         {"wetness.droplets[0]", "'radius'"}},
        {"{\"wetness\": {\"droplets\": [{\"center\": [0.5, 0.5], \"radius\": 0.1},"
         " {\"center\": [0.5, 0.5], \"radius\": -0.1}]}}",
         PELT_ERR_FORMAT, {"wetness.droplets[1].radius", "-0.1"}},
        {"{\"wetness\": {\"droplets\": [{\"center\": [0.5, 0.5], \"radius\": 0.1,"
         " \"radiu\": 1}]}}",
         PELT_ERR_FORMAT, {"'wetness.droplets[0].radiu'", "'wetness.droplets[0].radius'"}},
        {"{\"wetness\": {\"droplets\": [{\"center\": [0.5, 1.5], \"radius\": 0.1}]}}",
         PELT_ERR_FORMAT, {"wetness.droplets[0].center[1]"}},
        {"{\"wetness\": {\"droplets\": [3]}}", PELT_ERR_FORMAT, {"wetness.droplets[0]", "object"}},
        {"{\"wetness\": {\"drops\": {\"radius\": [0.1, 0.05]}}}", PELT_ERR_FORMAT,
         {"wetness.drops.radius", "min <= max"}},
        {"{\"wetness\": {\"rain\": {\"wetness\": [0, 2]}}}", PELT_ERR_FORMAT,
         {"wetness.rain.wetness[1]"}},
        {"{\"wetness\": {\"rain\": {\"start\": 2, \"stop\": 1}}}", PELT_ERR_FORMAT,
         {"wetness.rain.stop", "after"}},
        {"{\"wetness\": {\"mask_size\": 100000}}", PELT_ERR_FORMAT, {"wetness.mask_size"}},
        {"{\"wetness\": {\"clump_blend\": -0.1}}", PELT_ERR_FORMAT, {"wetness.clump_blend"}},
        {"{\"atlas\": {\"max_stretch\": 1.05}}", PELT_ERR_FORMAT, {"atlas.max_stretch", "1.1"}},
        {"{\"atlas\": {\"mode\": \"uv\"}}", PELT_ERR_FORMAT, {"atlas.mode", "mesh-uvs"}},
        {"[1, 2]", PELT_ERR_FORMAT, {"top level", "object"}},
        {"{\"fur\": {\"layers\": 16}} extra", PELT_ERR_FORMAT, {"line 1", "extra"}},
        {"", PELT_ERR_FORMAT, {"empty"}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        pelt_scene s;
        pelt_error err = {0};
        pelt_status st = pelt_scene_parse(cases[i].json, "dir/bad.json", &s, &err);
        CHECK(st == cases[i].status);
        CHECK(err.status == cases[i].status);
        if (st != cases[i].status) fprintf(stderr, "  case %zu: %s\n", i, cases[i].json);
        CHECK(strncmp(err.message, "dir/bad.json: ", 14) == 0);
        for (int w = 0; w < 3 && cases[i].words[w]; w++) CHECK(contains(err.message, cases[i].words[w]));
        /* a failed parse leaves the defaults and owns nothing */
        CHECK(is_default(&s));
    }
}

static void file_errors_name_the_file(void)
{
    pelt_scene s;
    pelt_error err = {0};

    CHECK(pelt_scene_load(SCENES "no_such_scene.json", &s, &err) == PELT_ERR_IO);
    CHECK(contains(err.message, "no_such_scene.json"));
    CHECK(is_default(&s));

    CHECK(pelt_scene_load(SCENES "syntax_line4.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "syntax_line4.json: line 4: JSON syntax error near"));

    CHECK(pelt_scene_load(SCENES "truncated.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "truncated.json"));
    CHECK(contains(err.message, "line 3"));
    CHECK(contains(err.message, "end of the file"));

    CHECK(pelt_scene_load(SCENES "empty.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "empty.json: empty file"));
    CHECK(pelt_scene_load(SCENES "blank.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "blank.json: empty file"));

    CHECK(pelt_scene_load(SCENES "nul_byte.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "nul_byte.json"));

    CHECK(pelt_scene_load(SCENES "bad_layers.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "bad_layers.json: fur.layers:"));
    CHECK(contains(err.message, "got -3"));

    CHECK(pelt_scene_load(SCENES "bad_typo.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "bad_typo.json: unknown key 'fur.lenght'"));

    /* a directory opens on Linux but cannot be read */
    CHECK(pelt_scene_load(SCENES, &s, &err) == PELT_ERR_IO);
    CHECK(contains(err.message, "scenes/"));
    CHECK(is_default(&s));
}

static void huge_file_is_refused(void)
{
    const char *path = PELT_TEST_OUT "/huge_scene.json";
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    /* valid JSON, one byte over the cap: the size alone must refuse it */
    size_t size = (size_t)PELT_SCENE_FILE_MAX + 1;
    static char spaces[65536];
    memset(spaces, ' ', sizeof spaces);
    fputc('{', f);
    size_t written = 1;
    while (written + 1 < size) {
        size_t n = size - 1 - written < sizeof spaces ? size - 1 - written : sizeof spaces;
        fwrite(spaces, 1, n, f);
        written += n;
    }
    fputc('}', f);
    fclose(f);

    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_load(path, &s, &err) == PELT_ERR_IO);
    CHECK(contains(err.message, "huge_scene.json"));
    CHECK(contains(err.message, "16 MiB"));
    remove(path);
}

static void deep_nesting_fails_cleanly(void)
{
    /* far deeper than cJSON's nesting limit: an error, not a stack overflow */
    size_t depth = 100000;
    char *text = malloc(2 * depth + 1);
    CHECK(text != NULL);
    if (!text) return;
    memset(text, '[', depth);
    memset(text + depth, ']', depth);
    text[2 * depth] = '\0';
    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_parse(text, "deep.json", &s, &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "deep.json"));
    free(text);
}

static void comment_keys_are_ignored(void)
{
    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_parse("{\"_comment\": \"hi\", \"fur\": {\"_note\": [1], \"layers\": 8}}",
                           "c.json", &s, &err) == PELT_OK);
    CHECK(s.fur.layers == 8);
    pelt_scene_free(&s);
}

static void set_overrides_and_validates(void)
{
    pelt_scene s;
    pelt_error err = {0};
    pelt_scene_defaults(&s);

    CHECK(pelt_scene_set(&s, "fur.layers", "32", &err) == PELT_OK);
    CHECK(s.fur.layers == 32);

    CHECK(pelt_scene_set(&s, "fur.layers", "-3", &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "--set: fur.layers:"));
    CHECK(contains(err.message, "-3"));
    CHECK(s.fur.layers == 32); /* unchanged on failure */

    CHECK(pelt_scene_set(&s, "fur.layers", "many", &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "\"many\""));

    CHECK(pelt_scene_set(&s, "fur.lenght", "0.1", &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "'fur.length'"));

    /* bare strings: a path and a name */
    CHECK(pelt_scene_set(&s, "mesh.file", "meshes/bunny.off", &err) == PELT_OK);
    CHECK(s.mesh.shape == PELT_SHAPE_FILE);
    CHECK(strcmp(s.mesh.file, "meshes/bunny.off") == 0);
    CHECK(pelt_scene_set(&s, "mesh.shape", "square", &err) == PELT_OK);
    CHECK(s.mesh.shape == PELT_SHAPE_SQUARE);
    CHECK(s.mesh.file[0] == '\0');
    CHECK(pelt_scene_set(&s, "mesh.shape", "file", &err) == PELT_ERR_FORMAT);
    CHECK(s.mesh.shape == PELT_SHAPE_SQUARE);
    CHECK(pelt_scene_set(&s, "mesh.file", "123", &err) == PELT_OK); /* a path, not a number */
    CHECK(strcmp(s.mesh.file, "123") == 0);
    CHECK(pelt_scene_set(&s, "mesh.shape", "\"torus\"", &err) == PELT_OK); /* quoted JSON */
    CHECK(s.mesh.shape == PELT_SHAPE_TORUS);
    CHECK(pelt_scene_set(&s, "mesh", "cow.off", &err) == PELT_OK);
    CHECK(s.mesh.shape == PELT_SHAPE_FILE && strcmp(s.mesh.file, "cow.off") == 0);

    CHECK(pelt_scene_set(&s, "fur.preset", "wavy", &err) == PELT_OK);
    CHECK(strcmp(s.fur_preset, "wavy") == 0);
    CHECK(pelt_scene_set(&s, "fur.preset", "curly", &err) == PELT_ERR_FORMAT);
    CHECK(strcmp(s.fur_preset, "wavy") == 0);
    CHECK(pelt_scene_set(&s, "fur.preset", "", &err) == PELT_OK);
    CHECK(s.fur_preset[0] == '\0');

    CHECK(pelt_scene_set(&s, "texture.image", "a.png", &err) == PELT_OK);
    CHECK(pelt_scene_set(&s, "texture.pattern", "spots", &err) == PELT_OK);
    CHECK(s.texture.pattern == PELT_COLOR_PATTERN_SPOTS && s.texture.image[0] == '\0');

    CHECK(pelt_scene_set(&s, "forces.wind", "[1, 0, -2]", &err) == PELT_OK);
    CHECK_NEAR(s.forces.wind[0], 1, 0);
    CHECK_NEAR(s.forces.wind[2], -2, 0);
    CHECK(pelt_scene_set(&s, "forces.wind", "1,0,0", &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "forces.wind"));

    /* a whole group */
    CHECK(pelt_scene_set(&s, "camera", "{\"yaw\": 10, \"distance\": 3}", &err) == PELT_OK);
    CHECK_NEAR(s.camera.yaw, 10, 0);
    CHECK_NEAR(s.camera.distance, 3, 0);
    CHECK_NEAR(s.camera.pitch, 25, 0);
    CHECK(pelt_scene_set(&s, "camera", "{\"yaw\": 10, \"fov\": 3}", &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "camera.fov"));

    /* arrays are replaced, the old one freed (ASan would see a leak) */
    CHECK(pelt_scene_set(&s, "wetness.droplets",
                         "[{\"center\": [0.1, 0.2], \"radius\": 0.05}]", &err) == PELT_OK);
    CHECK(s.wetness.droplet_count == 1);
    CHECK(pelt_scene_set(&s, "wetness.droplets",
                         "[{\"center\": [0.3, 0.4], \"radius\": 0.05},"
                         " {\"center\": [0.5, 0.6], \"radius\": 0.1, \"wetness\": 0.5}]",
                         &err) == PELT_OK);
    CHECK(s.wetness.droplet_count == 2);
    if (s.wetness.droplet_count == 2) CHECK_NEAR(s.wetness.droplets[1].center[1], 0.6, 1e-7);
    CHECK(pelt_scene_set(&s, "wetness.droplets", "[{\"center\": [0.3, 0.4]}]", &err) ==
          PELT_ERR_FORMAT);
    CHECK(s.wetness.droplet_count == 2);
    CHECK(pelt_scene_set(&s, "animation.wind", "[{\"time\": 0, \"wind\": [1,2,3]}]", &err) ==
          PELT_OK);
    CHECK(s.animation.wind_key_count == 1);
    CHECK(pelt_scene_set(&s, "wetness.droplets", "[]", &err) == PELT_OK);
    CHECK(s.wetness.droplet_count == 0);

    CHECK(pelt_scene_set(&s, "nothing", "1", &err) == PELT_ERR_FORMAT);
    CHECK(contains(err.message, "unknown key 'nothing'"));
    CHECK(pelt_scene_set(&s, NULL, "1", &err) == PELT_ERR_INVALID_ARGUMENT);
    pelt_scene_free(&s);
}

static void set_applies_on_top_of_a_loaded_file(void)
{
    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_load(SCENES "full.json", &s, &err) == PELT_OK);
    CHECK(pelt_scene_set(&s, "output.width", "64", &err) == PELT_OK);
    CHECK(s.output.width == 64);
    CHECK(s.output.height == 240); /* from the file */
    CHECK(s.wetness.droplet_count == 3);
    pelt_scene_free(&s);
}

static void wind_keyframes_interpolate_linearly(void)
{
    pelt_scene s;
    pelt_error err = {0};
    CHECK(pelt_scene_parse("{\"forces\": {\"wind\": [9, 9, 9]}, \"animation\": {\"wind\": ["
                           "{\"time\": 0, \"wind\": [0, 0, 0]},"
                           "{\"time\": 2, \"wind\": [4, 0, 0]},"
                           "{\"time\": 3, \"wind\": [4, 2, -1]}]}}",
                           "w.json", &s, &err) == PELT_OK);
    float w[3];
    pelt_scene_wind_at(&s, 1.0f, w); /* halfway along the first segment */
    CHECK_NEAR(w[0], 2, 1e-6);
    CHECK_NEAR(w[1], 0, 1e-6);
    pelt_scene_wind_at(&s, 2.5f, w);
    CHECK_NEAR(w[0], 4, 1e-6);
    CHECK_NEAR(w[1], 1, 1e-6);
    CHECK_NEAR(w[2], -0.5, 1e-6);
    pelt_scene_wind_at(&s, 2.0f, w); /* exactly on a key */
    CHECK_NEAR(w[0], 4, 1e-6);
    CHECK_NEAR(w[1], 0, 1e-6);
    pelt_scene_wind_at(&s, -1.0f, w); /* held before the first key */
    CHECK_NEAR(w[0], 0, 0);
    pelt_scene_wind_at(&s, 100.0f, w); /* and after the last */
    CHECK_NEAR(w[1], 2, 0);
    CHECK_NEAR(w[2], -1, 0);
    pelt_scene_wind_at(&s, NAN, w); /* never NaN out */
    CHECK(isfinite(w[0]) && isfinite(w[1]) && isfinite(w[2]));
    pelt_scene_free(&s);

    /* without keys the constant wind holds */
    pelt_scene_defaults(&s);
    s.forces.wind[2] = 3.0f;
    pelt_scene_wind_at(&s, 5.0f, w);
    CHECK_NEAR(w[2], 3, 0);
}

static void apply(const float m[16], const float p[3], float out[3])
{
    for (int r = 0; r < 3; r++) out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

static void model_at_turntable_rotates_about_y(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    float m[16], q[3];
    const float x[3] = {1, 0, 0};
    pelt_scene_model_at(&s, 3.0f, m); /* nothing animated: identity */
    for (int i = 0; i < 16; i++) CHECK_NEAR(m[i], (i % 5 == 0) ? 1 : 0, 1e-6);

    s.animation.turntable = 90.0f; /* a quarter turn per second */
    pelt_scene_model_at(&s, 1.0f, m);
    apply(m, x, q); /* +90 degrees about +Y takes +X to -Z */
    CHECK_NEAR(q[0], 0, 1e-6);
    CHECK_NEAR(q[1], 0, 1e-6);
    CHECK_NEAR(q[2], -1, 1e-6);
    pelt_scene_model_at(&s, 2.0f, m);
    apply(m, x, q);
    CHECK_NEAR(q[0], -1, 1e-6);
    CHECK_NEAR(q[2], 0, 1e-6);
}

static void model_at_shake_and_bounce(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    s.animation.shake_amplitude = 0.5f;
    s.animation.shake_frequency = 2.0f;
    s.animation.bounce_height = 0.3f;
    s.animation.bounce_frequency = 1.0f;
    float m[16];
    /* t = 1/8: shake phase 2 pi * 2 / 8 = pi/2 (peak), bounce |sin(pi/8)| */
    pelt_scene_model_at(&s, 0.125f, m);
    CHECK_NEAR(m[12], 0.5, 1e-6);
    CHECK_NEAR(m[13], 0.3 * sin(3.14159265358979 / 8), 1e-6);
    CHECK_NEAR(m[14], 0, 0);
    /* t = 1/2: bounce at its top, shake back at 0 */
    pelt_scene_model_at(&s, 0.5f, m);
    CHECK_NEAR(m[12], 0, 1e-6);
    CHECK_NEAR(m[13], 0.3, 1e-6);
    /* t = 1.5: |sin| keeps the bounce above the floor */
    pelt_scene_model_at(&s, 1.5f, m);
    CHECK_NEAR(m[13], 0.3, 1e-6);
    pelt_scene_model_at(&s, 1.0f, m);
    CHECK_NEAR(m[13], 0, 1e-6);
    for (float t = 0; t < 3; t += 0.01f) {
        pelt_scene_model_at(&s, t, m);
        CHECK(m[13] >= 0 && m[13] <= 0.3f + 1e-6f);
        CHECK(fabsf(m[12]) <= 0.5f + 1e-6f);
    }
}

static void model_at_applies_mesh_rotation_and_scale(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    s.mesh.scale = 2.0f;
    s.mesh.rotation[0] = 90.0f;
    float m[16], q[3];
    const float y[3] = {0, 1, 0};
    pelt_scene_model_at(&s, 0.0f, m);
    apply(m, y, q); /* scaled to 2, then +90 about X takes +Y to +Z */
    CHECK_NEAR(q[0], 0, 1e-6);
    CHECK_NEAR(q[1], 0, 1e-6);
    CHECK_NEAR(q[2], 2, 1e-6);
    /* X first, then Y: +Y -> +Z (X) -> +X (90 about Y takes +Z to +X) */
    s.mesh.scale = 1.0f;
    s.mesh.rotation[1] = 90.0f;
    pelt_scene_model_at(&s, 0.0f, m);
    apply(m, y, q);
    CHECK_NEAR(q[0], 1, 1e-6);
    CHECK_NEAR(q[2], 0, 1e-6);
}

static void shipped_scenes_all_parse(void)
{
    DIR *dir = opendir(SHIPPED);
    CHECK(dir != NULL);
    if (!dir) return;
    int count = 0;
    struct dirent *e;
    while ((e = readdir(dir)) != NULL) {
        size_t n = strlen(e->d_name);
        if (n < 6 || strcmp(e->d_name + n - 5, ".json") != 0) continue;
        char path[1024];
        snprintf(path, sizeof path, "%s%s", SHIPPED, e->d_name);
        pelt_scene s;
        pelt_error err = {0};
        pelt_status st = pelt_scene_load(path, &s, &err);
        CHECK(st == PELT_OK);
        if (st != PELT_OK) fprintf(stderr, "  %s\n", err.message);
        pelt_scene_free(&s);
        count++;
    }
    closedir(dir);
    /* default, wind-square, turntable, four Fig. 7 presets, rain */
    CHECK(count >= 8);
}

static void shipped_presets_give_four_different_fig7_looks(void)
{
    static const char *const files[4] = {"curl-straight.json", "curl-wavy.json",
                                         "curl-few-large.json", "curl-many-small.json"};
    float omega[4] = {0}, radius[4] = {0};
    for (int i = 0; i < 4; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s%s", SHIPPED, files[i]);
        pelt_scene s;
        pelt_error err = {0};
        CHECK(pelt_scene_load(path, &s, &err) == PELT_OK);
        /* the stored name is one the preset table knows */
        CHECK(pelt_fur_curl_look(s.fur_preset, &omega[i], &radius[i]));
        pelt_scene_free(&s);
    }
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            CHECK(omega[i] != omega[j] || radius[i] != radius[j]);
    /* straight has no curl; the "many small" curls turn faster than the few large */
    CHECK(radius[0] == 0 || omega[0] == 0);
    CHECK(omega[3] > omega[2]);
}

static void preset_accepts_both_spellings(void)
{
    static const char *const names[] = {"straight", "wavy", "few-large-curls",
                                        "many-small-curls", "large_curls", "small_curls"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        pelt_scene s;
        pelt_error err = {0};
        pelt_scene_defaults(&s);
        CHECK(pelt_scene_set(&s, "fur.preset", names[i], &err) == PELT_OK);
        float omega, radius;
        CHECK(pelt_fur_curl_look(s.fur_preset, &omega, &radius));
    }
}

/* Grooming keys land in scene.groom and scene.fur.look; strokes keep
 * their order and defaults (strength 1, at unset = NaN: by pixel). */
static void grooming_keys_and_strokes(void)
{
    pelt_scene s;
    pelt_error err = {0};
    const char *json = "{\"fur\": {\"groom\": \"g.ply\", \"length_map\": \"len.png\", "
                       "\"length_range\": [0.5, 2], \"flow_strength\": 0.5, "
                       "\"vertex_colors\": \"hair\", \"skin_color\": [0.1, 0.2, 0.3]},"
                       " \"strokes\": [{\"tool\": \"length\", \"radius\": 0.2, \"pixel\": [10, 20],"
                       " \"amount\": -0.5}, {\"tool\": \"comb\", \"radius\": 0.1, \"at\": [1, 2, 3],"
                       " \"drag\": [4, 5], \"strength\": 0.5}]}";
    CHECK(pelt_scene_parse(json, "dir/groom.json", &s, &err) == PELT_OK);
    CHECK(strcmp(s.groom.file, "dir/g.ply") == 0);
    CHECK(strcmp(s.groom.length_map, "dir/len.png") == 0);
    CHECK(s.groom.length_range[0] == 0.5f && s.groom.length_range[1] == 2.0f);
    CHECK(s.groom.density_range[0] == 0.0f && s.groom.density_range[1] == 1.0f);
    CHECK(s.groom.flow_strength == 0.5f);
    CHECK(s.groom.vertex_colors == PELT_VERTEX_COLORS_HAIR);
    CHECK(s.fur.look.skin_color[2] == 0.3f);
    CHECK(s.groom.stroke_count == 2);
    if (s.groom.stroke_count == 2) {
        const pelt_scene_stroke *a = &s.groom.strokes[0], *b = &s.groom.strokes[1];
        CHECK(a->brush.tool == PELT_BRUSH_LENGTH && a->brush.amount == -0.5f);
        CHECK(a->brush.strength == 1.0f && isnan(a->at[0]) && a->pixel[1] == 20.0f);
        CHECK(b->brush.tool == PELT_BRUSH_COMB && b->at[2] == 3.0f && b->drag[1] == 5.0f);
        CHECK(b->brush.strength == 0.5f);
    }
    /* --set replaces the list and frees the old one (ASan would tell). */
    CHECK(pelt_scene_set(&s, "strokes", "[{\"tool\": \"density\", \"radius\": 1, \"at\": [0,0,0]}]",
                         &err) == PELT_OK);
    CHECK(s.groom.stroke_count == 1 && s.groom.strokes[0].brush.tool == PELT_BRUSH_DENSITY);
    CHECK(pelt_scene_set(&s, "strokes", "[{\"tool\": 3}]", &err) != PELT_OK);
    CHECK(s.groom.stroke_count == 1);
    pelt_scene_free(&s);
    CHECK(s.groom.strokes == NULL && s.groom.stroke_count == 0);
}

static void forces_default_matches_dynamics_module(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    pelt_forces f = pelt_forces_default();
    CHECK(memcmp(&s.forces, &f, sizeof f) == 0);
}

int main(void)
{
    RUN(defaults_equal_table1);
    RUN(defaults_camera_light_forces);
    RUN(empty_object_gives_defaults);
    RUN(full_scene_sets_every_field);
    RUN(relative_paths_resolve_against_scene_dir);
    RUN(each_bad_value_names_file_and_key);
    RUN(file_errors_name_the_file);
    RUN(huge_file_is_refused);
    RUN(deep_nesting_fails_cleanly);
    RUN(comment_keys_are_ignored);
    RUN(set_overrides_and_validates);
    RUN(set_applies_on_top_of_a_loaded_file);
    RUN(wind_keyframes_interpolate_linearly);
    RUN(model_at_turntable_rotates_about_y);
    RUN(model_at_shake_and_bounce);
    RUN(model_at_applies_mesh_rotation_and_scale);
    RUN(shipped_scenes_all_parse);
    RUN(shipped_presets_give_four_different_fig7_looks);
    RUN(preset_accepts_both_spellings);
    RUN(forces_default_matches_dynamics_module);
    RUN(grooming_keys_and_strokes);
    return check_summary();
}
