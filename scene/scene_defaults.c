/* The scene's defaults and its release (pelt_scene_defaults, pelt_scene_free). */
#include "pelt/scene.h"

#include <stdlib.h>
#include <string.h>

void pelt_scene_defaults(pelt_scene *s)
{
    memset(s, 0, sizeof *s);

    s->mesh.shape = PELT_SHAPE_TORUS;
    s->mesh.major_radius = 1.0f;
    s->mesh.minor_radius = 0.4f;
    s->mesh.major_segments = 78; /* 78 * 60 * 2 = 9,360 triangles, Silva Table 1 */
    s->mesh.minor_segments = 60;
    s->mesh.radius = 1.0f;
    s->mesh.slices = 64;
    s->mesh.stacks = 32;
    s->mesh.size = 2.0f;
    s->mesh.subdivisions = 16;
    s->mesh.scale = 1.0f;

    /* The fur desc stays zero: pelt_fur_create puts in the defaults of its
     * rows (pelt/params.h), the one home of each. */

    s->texture.pattern = PELT_COLOR_PATTERN_NONE;

    s->camera.yaw = 30.0f;
    s->camera.pitch = 25.0f;
    s->camera.distance = 4.2f;
    s->camera.fov_y = 40.0f;

    s->light.direction[0] = 0.5f;
    s->light.direction[1] = 1.0f;
    s->light.direction[2] = 0.8f;
    s->light.color[0] = s->light.color[1] = s->light.color[2] = 1.0f;
    s->light.ambient = 0.25f;

    s->output.width = 800;
    s->output.height = 600;
    s->output.msaa = 4; /* GL 3.3 guarantees 4; thin hair aliases without */
    s->output.background[0] = 0.10f;
    s->output.background[1] = 0.11f;
    s->output.background[2] = 0.13f;
    s->output.background[3] = 1.0f;
    s->draw.exposure = 1.0f; /* output.exposure; output.tone: filmic (zero) */

    s->forces = pelt_forces_default();

    s->animation.frames = 1;
    s->animation.fps = 30.0f;
    s->animation.shake_frequency = 2.0f;
    s->animation.bounce_frequency = 1.0f;

    s->wetness.drops_seed = 1;
    s->wetness.drops_radius[0] = 0.02f;
    s->wetness.drops_radius[1] = 0.06f;
    s->wetness.drops_wetness[0] = 0.6f;
    s->wetness.drops_wetness[1] = 1.0f;
    s->wetness.rain.radius_min = 0.02f;
    s->wetness.rain.radius_max = 0.06f;
    s->wetness.rain.wetness_min = 0.6f;
    s->wetness.rain.wetness_max = 1.0f;
    s->wetness.rain.seed = 1;
    s->wetness.mask_image_wetness = 1.0f;

    s->strand_samples = 4;
    s->groom.length_range[1] = 1.0f;
    s->groom.density_range[1] = 1.0f;
    s->groom.flow_strength = 1.0f;
}

void pelt_scene_free(pelt_scene *s)
{
    if (!s) return;
    free(s->wetness.droplets);
    s->wetness.droplets = NULL;
    s->wetness.droplet_count = 0;
    free(s->animation.wind_keys);
    s->animation.wind_keys = NULL;
    s->animation.wind_key_count = 0;
    free(s->groom.strokes);
    s->groom.strokes = NULL;
    s->groom.stroke_count = 0;
}
