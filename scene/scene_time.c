/* A scene's animation at time t: the wind between its keys, the model's
 * spin and bounce (pelt_scene_wind_at, pelt_scene_model_at). */
#include "pelt/scene.h"

#include "core/base/vec.h"

#include <math.h>
#include <string.h>

#define PI_F 3.14159265358979f

void pelt_scene_wind_at(const pelt_scene *s, float t, float out[3])
{
    const pelt_wind_key *k = s->animation.wind_keys;
    size_t n = s->animation.wind_key_count;
    if (!k || n == 0) {
        memcpy(out, s->forces.wind, 3 * sizeof(float));
        return;
    }
    if (!isfinite(t)) t = 0.0f;
    if (t <= k[0].time) {
        memcpy(out, k[0].wind, 3 * sizeof(float));
        return;
    }
    if (t >= k[n - 1].time) {
        memcpy(out, k[n - 1].wind, 3 * sizeof(float));
        return;
    }
    /* k[lo].time <= t < k[hi].time */
    size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (k[mid].time <= t) lo = mid;
        else hi = mid;
    }
    float a = (t - k[lo].time) / (k[hi].time - k[lo].time);
    for (int i = 0; i < 3; i++) out[i] = k[lo].wind[i] + (k[hi].wind[i] - k[lo].wind[i]) * a;
}

void pelt_scene_model_at(const pelt_scene *s, float t, float model[16])
{
    const float deg = PI_F / 180.0f;
    const pelt_scene_mesh *m = &s->mesh;
    const pelt_scene_animation *a = &s->animation;
    if (!isfinite(t)) t = 0.0f;

    /* placement: scale, then X, Y, Z rotations */
    float r[16], tmp[16];
    pelt__mat4_identity(model);
    model[0] = model[5] = model[10] = m->scale;
    pelt__mat4_rotate(r, v3(1, 0, 0), m->rotation[0] * deg);
    pelt__mat4_mul(model, r, model);
    pelt__mat4_rotate(r, v3(0, 1, 0), m->rotation[1] * deg);
    pelt__mat4_mul(model, r, model);
    pelt__mat4_rotate(r, v3(0, 0, 1), m->rotation[2] * deg);
    pelt__mat4_mul(model, r, model);

    /* turntable about +Y; fmod keeps the angle small over long runs */
    float angle = fmodf(a->turntable * t, 360.0f) * deg;
    pelt__mat4_rotate(r, v3(0, 1, 0), angle);
    pelt__mat4_mul(tmp, r, model);

    /* shake along X, bounce along +Y: bounce_frequency hops per second */
    float x = a->shake_amplitude * sinf(2.0f * PI_F * a->shake_frequency * t);
    float y = a->bounce_height * fabsf(sinf(PI_F * a->bounce_frequency * t));
    memcpy(model, tmp, sizeof tmp);
    model[12] += x;
    model[13] += y;
}
