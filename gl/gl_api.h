/* Where the GL entry points come from: the one place that tells the
 * desktop build from the browser build (docs/web.md).
 *
 * Desktop: libepoxy, OpenGL 3.3 core and later, any extension by name.
 * Browser (Emscripten, WebGL2): OpenGL ES 3.0's header; Emscripten binds
 * each entry point to WebGL2 itself. PELT_GL_ES is 1 there and the rest
 * of pelt reads it to pick, at build time, what differs:
 *   - GLSL "#version 300 es" instead of "#version 330 core" (PELT_GLSL_VERSION,
 *     the first line of every shader: gl/programs.c, apps/view_hud.c)
 *   - no buffer textures: the strand reference does not draw (gl/strands_pass.c)
 *   - no pipeline statistics queries (pelt bench is desktop only). */
#ifndef PELT_GL_GL_API_H
#define PELT_GL_GL_API_H

#if defined(__EMSCRIPTEN__)
#include <GLES3/gl3.h>
#define PELT_GL_ES 1
#define PELT_GLSL_VERSION "#version 300 es\n"
#else
#include <epoxy/gl.h>
#define PELT_GL_ES 0
#define PELT_GLSL_VERSION "#version 330 core\n"
#endif

#endif
