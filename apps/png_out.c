/* PNG files out of the pelt command: render, compare and the viewer's
 * screenshots (apart from session.c so the browser build, which has no
 * headless context, writes them too). */
#include "apps/cli.h"

#include <errno.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <string.h>

bool cli_write_png(const char *cmd, const char *path, const uint8_t *rgba, unsigned w, unsigned h)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
        return false;
    }
    fclose(f);
    if (!stbi_write_png(path, (int)w, (int)h, 4, rgba, (int)w * 4)) {
        cli_error(cmd, "cannot write PNG '%s'", path);
        remove(path);
        return false;
    }
    return true;
}
