/* The strand reference (docs/reference.md, The strand reference): the
 * ground truth the shells and fins approximate. Each frame the hairs come
 * from core/fur/strand_ref.c (every strand of the fur texture's tile,
 * tiled over the fur uvs as the shells tile it, along the shells' curve at
 * its root) into one buffer texture; ONE draw turns each into a tapered
 * ribbon facing the eye (strand_vs.glsl), opaque, lit by the hairs' model
 * and the light's shadow maps. Its fragment stage is its own
 * (strand_fs.glsl): nothing of the shells' is shared. */
#include "gl/passes.h"

#include "core/base/hooks.h"
#include "core/fur/fur_gpu.h"
#include "gl/programs.h"

#include <string.h>

#if !PELT_GL_ES
static void build(pelt__strands_pass *p, unsigned features)
{
    char defines[PELT__FEATURE_DEFINES_MAX];
    pelt__shell_feature_defines(features, defines);
    const char *vs[] = {defines, pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_fur_light,
                        pelt__shader_strand_vs, NULL};
    const char *fs[] = {pelt__shader_shading, pelt__shader_strand_fs, NULL};
    if (pelt__gl_program_create("strand", vs, fs, &p->hooks, &p->variants[features], NULL) != PELT_OK) {
        p->failed[features] = true;
        return;
    }
    glUniform1i(glGetUniformLocation(p->variants[features], "u_strands"), PELT_UNIT_STRANDS);
    p->segments_uniform[features] = glGetUniformLocation(p->variants[features], "u_strand_segments");
}

#endif

void pelt__strands_pass_create(pelt__strands_pass *p, const pelt_fur *fur, const pelt_hooks *hooks)
{
    memset(p, 0, sizeof *p);
    p->hooks = *hooks;
    p->fur = fur;
}

#if PELT_GL_ES
/* GLSL ES 3.00 has no buffer textures (gl/gl_api.h): in the browser the
 * strand reference says so once and draws nothing. */
void pelt__strands_pass_draw(pelt__strands_pass *p, const pelt__pass_frame *f)
{
    if (!p->broken)
        pelt__log(&p->hooks.logger, PELT_LOG_ERROR,
                  "the strand reference needs buffer textures, which WebGL2 does not have: not drawn");
    p->broken = true;
    f->stats->strand_failures = 1;
}

void pelt__strands_pass_draw_light(pelt__strands_pass *p, const pelt__pass_frame *f)
{
    pelt__strands_pass_draw(p, f); /* says so once */
}
#else
/* Room for every hair of `segments` pieces: staging and the buffer
 * texture. Made on the first frame of strands and again only when the
 * curls need more pieces than there is room for. */
static bool reserve(pelt__strands_pass *p, unsigned segments)
{
    size_t bytes = (p->capacity ? p->capacity : 1) * 16 * (size_t)PELT__STRAND_TEXELS(segments);
    pelt__free(&p->hooks.allocator, p->hairs);
    p->hairs = pelt__alloc(&p->hooks.allocator, bytes);
    p->segments = p->hairs ? segments : 0;
    if (!p->hairs) return false;
    if (!p->buffer) glGenBuffers(1, &p->buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, p->buffer);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)bytes, NULL, GL_STREAM_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    if (!p->texture) glGenTextures(1, &p->texture);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_STRANDS);
    glBindTexture(GL_TEXTURE_BUFFER, p->texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, p->buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    return true;
}

/* The tile's strands and the hairs' storage: once, on the first frame of
 * strands. */
static bool make(pelt__strands_pass *p, unsigned segments)
{
    p->made = true;
    p->tile_count = pelt__strand_ref_tile(p->fur, NULL, 0);
    p->tile = pelt__alloc(&p->hooks.allocator, (p->tile_count ? p->tile_count : 1) * sizeof(pelt__furtex_strand));
    if (!p->tile) return false;
    pelt__strand_ref_tile(p->fur, p->tile, p->tile_count);
    p->capacity = pelt__strand_ref_count(p->fur, p->tile, p->tile_count);
    return reserve(p, segments);
}

/* This frame's hairs into the buffer texture; how many (0: none, or the
 * pass is broken and says so in the stats). */
static size_t upload_hairs(pelt__strands_pass *p, const pelt__pass_frame *f, unsigned segments)
{
    if (!p->broken && (p->made ? segments > p->segments && !reserve(p, segments) : !make(p, segments))) {
        p->broken = true;
        pelt__log(&p->hooks.logger, PELT_LOG_ERROR, "out of memory for the strand reference's %zu hairs",
                  p->capacity);
    }
    if (p->broken) {
        f->stats->strand_failures = 1;
        return 0;
    }
    size_t n = pelt__strand_ref_build(p->fur, p->tile, p->tile_count, segments, p->hairs, p->capacity);
    if (n == 0) return 0;
    size_t bytes = n * 16 * (size_t)PELT__STRAND_TEXELS(segments);
    glBindBuffer(GL_TEXTURE_BUFFER, p->buffer);
    glBufferSubData(GL_TEXTURE_BUFFER, 0, (GLsizeiptr)bytes, p->hairs);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    f->stats->upload_bytes += bytes;
    return n;
}

void pelt__strands_pass_draw(pelt__strands_pass *p, const pelt__pass_frame *f)
{
    unsigned segments = pelt__strand_ref_segments(p->fur);
    /* The light pass, earlier in the frame, built and uploaded them already. */
    size_t n = p->light_hairs ? p->light_hairs : upload_hairs(p, f, segments);
    p->light_hairs = 0;
    if (n == 0) return;
    unsigned features = f->shell_features & PELT__STRAND_FEATURES;
    if (!p->variants[features] && !p->failed[features]) build(p, features);
    if (!p->variants[features]) {
        f->stats->strand_failures = 1; /* the compiler's log went to the logger */
        return;
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_STRANDS);
    glBindTexture(GL_TEXTURE_BUFFER, p->texture);
    glUseProgram(p->variants[features]);
    glUniform1i(p->segments_uniform[features], (GLint)segments);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(n * 6 * segments));
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    f->stats->strand_draw_calls++;
    f->stats->strands += n;
    f->stats->triangles += n * 2 * segments;
}

void pelt__strands_pass_draw_light(pelt__strands_pass *p, const pelt__pass_frame *f)
{
    unsigned segments = pelt__strand_ref_segments(p->fur);
    size_t n = upload_hairs(p, f, segments);
    p->light_hairs = n; /* the frame's draw of the hairs follows (gl/renderer.c) */
    if (n == 0) return;
    if (!p->light_program && !p->light_failed) {
        static const char light_define[] = "#define PELT_LIGHT_PASS 1\n";
        const char *vs[] = {light_define, pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_fur_light,
                            pelt__shader_strand_vs, NULL};
        const char *fs[] = {light_define, pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_strand_fs,
                            NULL};
        if (pelt__gl_program_create("strand light", vs, fs, &p->hooks, &p->light_program, NULL) == PELT_OK) {
            glUniform1i(glGetUniformLocation(p->light_program, "u_strands"), PELT_UNIT_STRANDS);
            p->light_segments = glGetUniformLocation(p->light_program, "u_strand_segments");
        } else {
            p->light_failed = true;
        }
    }
    if (!p->light_program) {
        f->stats->strand_failures = 1;
        return;
    }
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_STRANDS);
    glBindTexture(GL_TEXTURE_BUFFER, p->texture);
    glUseProgram(p->light_program);
    glUniform1i(p->light_segments, (GLint)segments);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(n * 6 * segments));
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    f->stats->shadow_draw_calls++;
    f->stats->triangles += n * 2 * segments;
}

#endif

void pelt__strands_pass_destroy(pelt__strands_pass *p)
{
    for (unsigned k = 0; k <= PELT__STRAND_FEATURES; k++)
        if (p->variants[k]) glDeleteProgram(p->variants[k]);
    if (p->light_program) glDeleteProgram(p->light_program);
    if (p->texture) glDeleteTextures(1, &p->texture);
    if (p->buffer) glDeleteBuffers(1, &p->buffer);
    pelt__free(&p->hooks.allocator, p->tile);
    pelt__free(&p->hooks.allocator, p->hairs);
    memset(p, 0, sizeof *p);
}
