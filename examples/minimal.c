/* The smallest pelt program: a furry torus, stepped and drawn for a few
 * frames into a headless context. In an engine, skip pelt_headless_* and
 * call the same functions with your own OpenGL 3.3+ context current. */
#include <pelt/pelt.h>

#include <stdio.h>

int main(void)
{
    pelt_error err = {0};
    pelt_headless *gl = NULL;
    pelt_mesh *mesh = NULL;
    pelt_fur *fur = NULL;
    pelt_renderer *renderer = NULL;
    int rc = 1;

    if (pelt_headless_create(&(pelt_headless_desc){320, 240, 0, false}, &gl, &err) != PELT_OK ||
        pelt_mesh_torus(1.0f, 0.4f, 78, 60, &mesh, &err) != PELT_OK ||
        pelt_fur_create(mesh, &(pelt_fur_desc){.layers = 16}, &fur, &err) != PELT_OK ||
        pelt_renderer_create(mesh, fur, NULL, &renderer, &err) != PELT_OK) {
        fprintf(stderr, "pelt: %s\n", err.message);
        goto done;
    }

    pelt_view view = {0};
    pelt_camera_to_view(&(pelt_camera){.yaw = 30, .pitch = 25, .distance = 4.2f, .fov_y = 40},
                        320.0f / 240.0f, &view);
    view.light = (pelt_light){{0.5f, 1.0f, 0.8f}, {1.0f, 1.0f, 1.0f}, 0.25f};
    pelt_forces forces = pelt_forces_default();
    forces.wind[0] = 10.0f;

    /* A drop of water where a ray from the camera hits the torus. */
    float down[3] = {0.0f, -1.0f, 0.0f}, above[3] = {1.0f, 2.0f, 0.0f};
    pelt_fur_add_droplet_ray(fur, above, down, 0.1f, 1.0f);

    for (int frame = 0; frame < 30; frame++) {
        pelt_fur_set_transform(fur, view.model, NULL);
        pelt_fur_step(fur, 1.0f / 60.0f, &forces);
        pelt_renderer_draw(renderer, &view, NULL); /* into the bound framebuffer */
    }
    pelt_render_stats stats = pelt_renderer_get_stats(renderer);
    printf("drew 30 frames, %u shell draw call per frame for %u layers\n",
           stats.shell_draw_calls, stats.shell_instances);
    rc = 0;
done:
    pelt_renderer_destroy(renderer);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(mesh);
    pelt_headless_destroy(gl);
    return rc;
}
