/* What the fuzz targets share: a quiet logger, one small furry torus made
 * once per process (libFuzzer calls the target many times), and what the
 * scene targets do with a scene they parsed. */
#ifndef PELT_FUZZ_COMMON_H
#define PELT_FUZZ_COMMON_H

#include <pelt/pelt.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static inline void fuzz_quiet(pelt_log_level level, const char *message, void *user)
{
    (void)level, (void)message, (void)user;
}

/* A 12 x 8 torus with a 64 x 64 fur texture and mask: small enough that
 * loading a groom or painting an image is fast. Aborts when it cannot be
 * made (that is a broken build, not a finding). */
static inline pelt_fur *fuzz_torus_fur(void)
{
    static pelt_mesh *mesh;
    static pelt_fur *fur;
    if (fur) return fur;
    pelt_error err = {0};
    pelt_fur_desc d = {.layers = 4, .seed = 7};
    d.hooks.logger.func = fuzz_quiet;
    d.look.texture_size = 64;
    d.wet.mask_size = 64;
    if (pelt_mesh_torus(1.0f, 0.4f, 12, 8, &mesh, &err) != PELT_OK ||
        pelt_fur_create(mesh, &d, &fur, &err) != PELT_OK) {
        fprintf(stderr, "fuzz: cannot make the torus fur: %s\n", err.message);
        abort();
    }
    return fur;
}

/* What the scene targets do with a scene they got: its wind and model at
 * time t (pelt_scene_wind_at, pelt_scene_model_at), then free it. */
static inline void fuzz_use_scene(pelt_scene *s, float t)
{
    float wind[3], model[16];
    pelt_scene_wind_at(s, t, wind);
    pelt_scene_model_at(s, t, model);
    pelt_scene_free(s);
}

#endif
