/* Images a scene names (colour texture, mask image, groom maps), decoded
 * with stb_image after a check of the size their header declares. */
#ifndef PELT_SCENE_IMAGE_H
#define PELT_SCENE_IMAGE_H

#include "pelt/base.h"

#include <stddef.h>
#include <stdint.h>

#define PELT__IMAGE_MAX_SIDE 16384
#define PELT__IMAGE_MAX_PIXELS (1LL << 26) /* 256 MiB as RGBA */

/* Decodes size bytes of an image file into *px with `channels` channels
 * (free with stbi_image_free). Messages start with key and name the file;
 * an image larger than the limits above is PELT_ERR_FORMAT before stb
 * allocates anything. */
pelt_status pelt__scene_decode_image(const char *key, const char *name, const uint8_t *data,
                                     size_t size, int channels, uint8_t **px, int *w, int *h,
                                     pelt_error *err);

/* Loads an image file into *px (free with stbi_image_free); errors name the
 * scene key and the file, with the system's reason when the file cannot be
 * read. */
pelt_status pelt__scene_load_image(const char *key, const char *path, int channels, uint8_t **px,
                                   int *w, int *h, pelt_error *err);

#endif
