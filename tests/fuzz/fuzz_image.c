/* Fuzz target: an image file as the scene runner reads its colour texture,
 * mask image and groom maps (pelt__scene_decode_image), then handed to what
 * consumes each: the colour texture, the wetness painter, a groom map. */
#include "fuzz_common.h"

#include "scene/scene_image.h"

#include <stb_image.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pelt_fur *fur = fuzz_torus_fur();
    pelt_error err = {0};
    int w, h;
    uint8_t *px;
    if (pelt__scene_decode_image("texture.image", "fuzz.png", data, size, 4, &px, &w, &h, &err) ==
        PELT_OK) {
        pelt_fur_set_color_texture(fur, px, (unsigned)w, (unsigned)h, &err);
        pelt_fur_groom_from_image(fur, (pelt_groom_field)(size % 4), px, (unsigned)w, (unsigned)h,
                                  0.5f, 1.5f, &err);
        stbi_image_free(px);
    }
    if (pelt__scene_decode_image("wetness.mask_image", "fuzz.png", data, size, 1, &px, &w, &h,
                                 &err) == PELT_OK) {
        pelt_fur_paint_wetness(fur, px, (unsigned)w, (unsigned)h, 1.0f, &err);
        stbi_image_free(px);
    }
    pelt_fur_reset_groom(fur);
    pelt_fur_clear_wetness(fur);
    return 0;
}
