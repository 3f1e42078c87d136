/* The GL state contract of pelt/render.h, in code: what every upload
 * assumes, and what every call leaves behind (GL's initial values, so a
 * caller's render loop finds the context as a fresh one would be). Fixed
 * values rather than a saved copy: no glGet in the per-frame path. */
#include "gl/gpu.h"

void pelt__gl_unpack_defaults(void)
{
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4); /* RGBA8 and RGBA32F rows are multiples of 4 */
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 0);
}

void pelt__gl_state_reset(void)
{
    glUseProgram(0);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint i = 0; i < PELT_BLOCK_COUNT; i++) glBindBufferBase(GL_UNIFORM_BUFFER, i, 0);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    for (GLenum u = 0; u < PELT_UNIT_COUNT; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    pelt__gl_unpack_defaults();
}

void pelt__gl_blended_hair_state(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* Alpha accumulates as coverage, so an opaque background stays opaque. */
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}
