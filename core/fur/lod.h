/* Geometric level of detail for the shells (beyond Lengyel et al. 2001
 * §2.4, see docs/lod.md): simplified triangle lists of the mesh made with
 * meshoptimizer over the SAME vertices, so strands, uvs, the atlas and the
 * wetness mask are shared by every level. Each level has its own fins (its
 * edges). The skin keeps the full mesh. No GL here. */
#ifndef PELT_CORE_FUR_LOD_H
#define PELT_CORE_FUR_LOD_H

#include "core/fur/fins.h"
#include "pelt/mesh.h"

#include <stdbool.h>

#define PELT__LOD_MAX_LEVELS 12
/* The levels whose normals are fitted to the full mesh's (lod_normals.c):
 * the coarser ones are drawn where the fur is too short on screen for a
 * hair's turn to show. */
#define PELT__LOD_FIT_LEVELS 4

typedef struct pelt__lod_level {
    uint32_t *indices;      /* 3 per triangle, in vertex-cache order */
    size_t triangle_count;
    pelt__fin_edge *fins;   /* the level's edges (core/fur/fins.h) */
    float *fin_normals;     /* 3 per fin: pelt__fin_normal, for the fade of
                               the fins a view shows (fin_frame.c) */
    size_t fin_count;
    uint32_t *fin_vertices; /* the vertices the fins stand on, ascending */
    size_t fin_vertex_count;
    uint32_t *fin_ends;     /* 2 per fin: its a and b as indices into fin_vertices */
    float error;            /* mesh units: how far the level's surface strays
                               from the full mesh (meshoptimizer's measure) */
    float edge;             /* mesh units: the mean edge length, how far apart
                               the level samples strands, groom and light */
    float *fit_normals;     /* 3 per vertex (the mesh's), levels 1 to
                               PELT__LOD_FIT_LEVELS, else NULL: each kept
                               vertex's fitted normal less its own, in its
                               frame (pelt__lod_fit_normals) */
} pelt__lod_level;

typedef struct pelt__lod_chain {
    pelt__lod_level levels[PELT__LOD_MAX_LEVELS]; /* 0: the full mesh */
    unsigned count;
    float center[3], radius; /* the mesh's bounding sphere, mesh units */
    bool closed;             /* every edge shared by two triangles (positions
                                welded): back-facing shells may be culled */
    int winding;             /* +1: triangles wind counter-clockwise about
                                the vertex normals, -1 clockwise, 0 mixed */
} pelt__lod_chain;

/* Builds level 0 (the mesh's triangles in vertex-cache order) and coarser
 * levels of about half the triangles each, borders and uv seams
 * kept, until a level stops shrinking, up to PELT__LOD_MAX_LEVELS or
 * `max_levels` (1: level 0 only). Every block comes from `alloc`. */
pelt_status pelt__lod_chain_build(const pelt_mesh *mesh, uint32_t seed, unsigned max_levels,
                                  const pelt_allocator *alloc, pelt__lod_chain *out, pelt_error *err);
void pelt__lod_chain_free(pelt__lod_chain *c, const pelt_allocator *alloc);

/* A coarse level's normals fitted to the full mesh's (lod_normals.c): the
 * level's triangles interpolate its kept vertices' normals over the
 * vertices it left out, so the hairs there turn; the kept normals are
 * fitted by least squares so that their interpolation meets the full
 * mesh's normal at every vertex. Writes, for each of the mesh's vertices,
 * the fitted unit normal less its own in its frame (u the tangent, v =
 * n x u times the handedness, n): 0 where the level left the vertex out.
 * `cell`: the grid's cell, about the level's mean edge. */
pelt_status pelt__lod_fit_normals(const pelt_mesh_data *m, const float *tangents, const uint32_t *indices,
                                  size_t triangles, float cell, const pelt_allocator *alloc, float *out,
                                  pelt_error *err);

/* The hair's normal on a level: normalize(n + d.x u + d.y v + d.z n), d
 * from fit_normals. Mirrors level_fit_normal (shell_vs.glsl). */
void pelt__lod_fit_normal(const float n[3], const float u[3], const float v[3], const float d[3], float out[3]);

/* The coarsest level whose error, seen from where it is largest on screen,
 * stays within `max_error_px` pixels and whose mean edge within
 * `max_edge_px` (strands, groom and light are sampled per vertex: coarser
 * would blur them). `pixels_per_unit` is the projected size of one mesh
 * unit at the mesh's nearest point (0 or less, or not finite: level 0). */
unsigned pelt__lod_pick(const pelt__lod_chain *c, float pixels_per_unit, float max_error_px, float max_edge_px);

/* The fins' level: the coarsest level from `mesh_level` on whose error on
 * screen stays within max_error_px and whose mean edge (mesh units) is at
 * most max_edge, the fin texture's slab: a fin shows the hair of a slab
 * along its edge, so fins closer than a slab only overlap (each is drawn
 * the fainter, pelt__fin_spacing_opacity), and on llvmpipe a fin costs its
 * pixels whatever it shows. The shells' edge bound on screen is for
 * lighting and shaping across a triangle, which a fin does not do. */
unsigned pelt__lod_pick_fins(const pelt__lod_chain *c, unsigned mesh_level, float pixels_per_unit, float max_error_px,
                             float max_edge);

/* Pixels per mesh unit at the bounding sphere's nearest point to the eye:
 * `proj_y` is the projection's [1][1] (cot of half the vertical field of
 * view), `height` the viewport's, `scale` the model matrix's largest
 * scale and `distance` from the eye to the sphere's centre, all in world
 * units. Infinity when the eye is inside the sphere. Mirrors nothing in
 * GLSL: the renderer picks levels on the CPU. */
float pelt__lod_pixels_per_unit(float proj_y, float height, float scale, float distance, float radius);

/* ---- shell levels (Lengyel et al. 2001 §2.4) ----
 * Level k has ceil(N / 2^k) shells, anchored at the outermost: its shells
 * sit at layers n = N - 1 - 2^k j, j = 0, 1, ...; the shell at n of level
 * k + 1 is level k's shell at n composited over level k's at n - 2^k (the
 * pairs become the coarser level's "even" shells, the others are left
 * out). Levels run until one shell remains. In the volume, level 0 is
 * slices 1..N (slice 0 the skin) and each coarser level follows, inner
 * shell first. */
unsigned pelt__lod_shell_levels(unsigned layers);            /* levels, level 0 included */
unsigned pelt__lod_shell_count(unsigned layers, unsigned level);
unsigned pelt__lod_shell_base(unsigned layers, unsigned level); /* its first slice */
size_t pelt__lod_shell_extra_slices(unsigned layers);       /* slices beyond N + 1 */
/* Layer n of the i-th shell of a level, inner first. */
unsigned pelt__lod_shell_layer(unsigned layers, unsigned level, unsigned i);

/* The shell pass's draw of a level (gl/shell_pass.c): shells = (shells from
 * the draw's first to the outermost, step 2^level, slice of instance 0,
 * blend), next = (the next level's first slice, its shell count); the
 * instance count goes to *count. Level 0 without a blend may start at
 * layer `first` (pelt_draw_desc.first_layer); other levels ignore it. */
void pelt__lod_shell_uniforms(unsigned layers, unsigned level, float blend, unsigned first, float shells[4],
                              float next[2], unsigned *count);

/* Instance i of such a draw, mirroring shell_instance() in
 * gl/shaders/shell_lod.glsl: returns its layer n; slices = (its slice, the
 * next level's slice it blends into, the blend: 0 for the shells that fade
 * out), *alpha = its opacity (1 - blend when it fades out). */
float pelt__lod_shell_instance(const float shells[4], const float next[2], float layers, float i, float slices[3],
                               float *alpha);

/* The view's shell budget (docs/lod.md): fur seen face-on shows its
 * shells' spacing foreshortened by sin(theta), theta between the fur's
 * normal and the direction to the eye, so a vertex seen face-on needs
 * fewer shells than one seen edge-on, where shells closer than the pixels
 * alias into stripes. side_px is the drawn level's spacing in pixels were
 * the fur at this vertex seen side-on, n_dot_v = cos(theta). Returns how
 * far the vertex goes towards half the shells,
 *   w = clamp(log2(target_px / (side_px sin(theta))), 0, 1):
 * the level's odd shells (from the outside) fade by 1 - w and each even
 * shell stands for itself and the faded one below it, its premultiplied
 * texel composited over itself by w (pelt__lod_view_texel): the hair of
 * neighbouring slices is nearly the same, and it costs no second fetch.
 * A curled hair also moves sideways from one layer to the next, drift
 * times the spacing (pelt__lod_shell_hair_drift), in the surface's plane,
 * which a face-on view shows whole: the spacing the budget weighs is
 * side_px sqrt(sin^2(theta) + drift^2), so that curls keep the shells that
 * draw each turn (docs/method.md, Shells a turn of the curl); straight hair
 * (drift 0) as above. Mirrors shell_view_blend() in
 * gl/shaders/shell_lod.glsl. */
float pelt__lod_view_blend(float side_px, float n_dot_v, float target_px, float drift);

/* The back-facing shells of a closed mesh seen without fins: the skin
 * hides them unless they stand near the silhouette, where their hair
 * crosses the outline. A vertex is left out (moved beyond the far plane)
 * where n_dot_v < -reach; a negative reach keeps every one. Mirrors
 * shell_back_hidden() in gl/shaders/shell_lod.glsl. */
bool pelt__lod_back_hidden(float n_dot_v, float reach);

/* The mip level the shells read their fur texture at, from the screen
 * derivatives of the fur uv (tiles per pixel along x and along y) and the
 * texture's size in texels: the footprint's longer side over max_aniso,
 * or its shorter side where that is longer,
 *   lod = log2(max(max(|dx|, |dy|) texels / max_aniso, min(|dx|, |dy|) texels)).
 * A texture read picks the level from the longer side, so fur seen at a
 * grazing angle, whose footprint is long across the view and short along
 * it, blurs along both; this keeps its hairs sharp across the view with
 * one fetch (up to PELT__FUR_TEXTURE_ANISO texels along the long side to
 * a pixel). Mirrors fur_texture_lod() in gl/shaders/shell_lod.glsl. */
#define PELT__FUR_TEXTURE_ANISO 4.0f
float pelt__lod_fur_texture(const float dx[2], const float dy[2], float texels, float max_aniso);

/* The level the shells read at: pelt__lod_fur_texture's, half a level
 * finer where the footprint is round. The fur texture is read from the
 * nearest mip level (GL_LINEAR_MIPMAP_NEAREST): at the footprint's own
 * level that rounds up to half a level coarser, texels up to 1.4 pixels a
 * side, filtered bilinearly over two of them: wider than the pixel's own
 * box, the filter the strand reference's supersampling applies, so the
 * shells came out softer than the hairs they stand for. Half a level finer
 * the nearest level is the footprint's rounded down: no texel larger than
 * the pixel. The sharpening falls linearly
 * to none where the footprint is twice as long as wide: fur seen at a
 * grazing angle is already read finer than the pixel across it (max_aniso),
 * and sharper still its layers' rows cross-hatch the rim and crawl as it
 * moves. The fins keep the footprint's level: sharper, their sparse hair
 * drops out of the outline seen from afar (docs/reference.md, The fur
 * texture read half a level sharper). Mirrors shell_fur_texture_lod() and
 * FUR_TEXTURE_SHARPEN in shell_lod.glsl. */
#define PELT__FUR_TEXTURE_SHARPEN 0.5f
float pelt__lod_shell_fur_texture(const float dx[2], const float dy[2], float texels, float max_aniso);

/* The shells' read in n fetches (lod.texture_taps up to max_taps): a
 * footprint longer than max_aniso times its shorter side takes
 *   n = min(ceil(longer / (max_aniso shorter)), max_taps)
 * fetches spaced evenly along its longer side, each at the level of its
 * n-th part, log2(max(longer / (max_aniso n), shorter)): what anisotropic
 * filtering does, so fur seen at a grazing angle keeps its hairs n times
 * sharper across the view without aliasing along it. One fetch reads at
 * pelt__lod_shell_fur_texture's level. Returns n and writes the level.
 * Mirrors fur_texture_taps() in gl/shaders/shell_lod.glsl. */
unsigned pelt__lod_fur_texture_taps(const float dx[2], const float dy[2], float texels, float max_aniso,
                                    unsigned max_taps, float *lod);

/* The fins read their texture the same way (derivatives in texels, texels
 * 1): a fin is one quad, whose hair is foreshortened up the fin, and has no
 * rows to turn into stripes. Their max_aniso is PELT__FIN_TEXTURE_ANISO
 * where the footprint's shorter side is a texel or less, 1 (a texture
 * read's own level) from 2 texels, linear between: seen from further, the
 * fin's hair is finer than a pixel both ways and a sharper read only
 * aliases it (the outline's faint hair drops out). Mirrors
 * fin_texture_aniso() and FIN_TEXTURE_ANISO in shell_lod.glsl. */
#define PELT__FIN_TEXTURE_ANISO 4.0f
float pelt__lod_fin_texture_aniso(const float dx[2], const float dy[2]);

/* The max_aniso of pelt__lod_fur_texture at a vertex: max_aniso
 * (lod.texture_aniso, default PELT__FUR_TEXTURE_ANISO) where the shells lie
 * at most PELT__FUR_TEXTURE_ROW_PX apart on screen,
 * 1 (a texture read's own level) from twice that, linear between: where
 * the shells stand far enough apart to show as rows, a sharper texture
 * makes the rows stripes. side_px and n_dot_v as pelt__lod_view_blend's.
 * Mirrors fur_texture_aniso() in gl/shaders/shell_lod.glsl. */
#define PELT__FUR_TEXTURE_ROW_PX 0.7f
float pelt__lod_fur_texture_aniso(float side_px, float n_dot_v, float max_aniso);

/* Close up, the sub shells a layer is drawn as (lod.sub_shells, docs/lod.md):
 * where the shells stand more than PELT__SUB_SHELL_PIXELS apart on screen
 * seen side-on (side_px, at the fur nearest the eye), edge-on they show as
 * rows and the fur texture may not be read sharp across them
 * (pelt__lod_fur_texture_aniso); k shells a layer, evenly down to the one
 * below, stand side_px / k apart. ceil(side_px / PELT__SUB_SHELL_PIXELS),
 * 1 .. max_sub. */
#define PELT__SUB_SHELL_PIXELS 1.4f
unsigned pelt__lod_sub_shells(float side_px, unsigned max_sub);

/* How far a vertex needs the frame's sub shells, 0..1: its layers' spacing
 * on screen, side_px foreshortened as the view's budget weighs it
 * (pelt__lod_view_blend: side_px sqrt(sin^2(theta) + drift^2)), from 0.35
 * of PELT__SUB_SHELL_PIXELS (0) to PELT__SUB_SHELL_PIXELS (1): close up,
 * the fur seen face-on stands its layers close and draws one a layer.
 * Not from 1.4 px down only: a hair drawn by shells less than a pixel
 * apart shows as a chain of beads where the read is sharp, and k shells
 * a layer join them (docs/lod.md).
 * Mirrors sub_shell_need() in gl/shaders/shell_lod.glsl. */
float pelt__lod_sub_shell_need(float side_px, float n_dot_v, float drift);

/* The exponent of sub shell `part` (0 the innermost) of k in its layer's
 * coverage, 1 - (1 - a)^e, where the vertex needs them `need`: the k - 1
 * below the layer take need / k each and the layer's own the rest, so the
 * k together cover what the layer did (at need 1 each 1/k, at 0 the
 * layer's own alone; the others, at 0, are clipped). Mirrors
 * sub_shell_exponent(). */
float pelt__lod_sub_shell_exponent(float part, float k, float need);

/* The hair's edge seen close: a hair's coverage in the fur texture ramps
 * from 0 to 1 over about a texel, and coverage 0.5 is the hair's edge. Where
 * a texel spans several pixels on screen, so does the ramp, and the shells
 * draw each hair wider and softer than it is (fat, bright blobs where the
 * hairs are thin lines with the dark depth between them). The gain is the
 * pixels a texel spans along the footprint's longer side (derivatives as
 * pelt__lod_fur_texture's), at least 1: 1 wherever the texture is read at
 * a pixel a texel or less. Mirrors fur_edge_gain() in shell_lod.glsl. */
float pelt__lod_fur_edge_gain(const float dx[2], const float dy[2], float texels);

/* A premultiplied texel with its coverage a steepened by gain about the
 * hair's edge, a' = clamp((a - 0.5) gain + 0.5, 0, 1), so that the ramp
 * spans a pixel; colour, height and id keep their ratio to coverage. gain
 * 1 leaves it as it is. Mirrors fur_edge() in shell_lod.glsl. */
void pelt__lod_fur_edge(float rgba[4], float gain);

/* The shells count a hair's edge more than once: a ray of sight that
 * runs along a hair crosses it in k consecutive shells, and each shell
 * holds the same cross-section, so a texel of coverage a composites to
 * 1 - (1 - a)^k where the hair covers a. k is the hair's width over the
 * distance the ray moves sideways, relative to the hair, from one shell
 * to the next: the layer spacing times tan of the angle between the ray
 * and the hair (cos_view = |T.V|), plus the hair's own drift per spacing
 * (its curl in the fur texture, its ringlet), in quadrature. width_over_
 * spacing is the hair's width over the layer spacing. Between `least`
 * and `cap` (pelt__lod_shell_overcount_cap): past a few shells the
 * texture's hairs lean and bend off the ray, which then meets other hairs
 * (docs/reference.md, The shells count a hair's edge once). `least` is 1
 * but where the surface is seen edge-on (pelt__lod_shell_edge_least): a
 * count below 1 raises the shell's coverage to stand for 1/k crossings of
 * the hair. Mirrors shell_overcount() in gl/shaders/shell_lod.glsl. */
float pelt__lod_shell_overcount(float width_over_spacing, float cos_view, float drift, float least, float cap);

/* The cos_view pelt__lod_shell_overcount takes, for a hair of unit tangent
 * t seen along the unit ray V over a surface of unit normal n: the shells
 * are planes along n, so from one shell to the next the hair moves t/(t.n)
 * and the ray V/(V.n), and the ray moves sideways against the hair by
 * |t/(t.n) - V/(V.n)| per unit of height: the cos of the angle whose
 * tan that is. For a hair standing along n it is |T.V|; for a combed or
 * hanging hair the angle between the two says more or less than the
 * shells do (docs/reference.md, A leaning hair in the shells' stack).
 * 0 where the hair or the ray lies in the shells' plane. Mirrors
 * shell_stack_cos() in shell_lod.glsl. */
float pelt__lod_shell_stack_cos(const float t[3], const float V[3], const float n[3]);

/* A hair seen from the side between two shells (docs/reference.md, Hairs
 * seen from the side, not beads). Each shell holds the hair's
 * cross-section; seen at a grazing angle, the section of a hair standing
 * up is a short dash and the next shell's lies one spacing lower on
 * screen: the hair reads as a chain of beads. The shell fragment also
 * reads the fur texture half a gap back and takes the union of the two
 * (shell_fs.glsl), so each shell holds the hair down to the next. The gap,
 * in fur-texture tiles: the point of this shell's plane that lies, seen
 * from the eye, where the hair's point one shell lower does, less the
 * hair's point on this shell: V (step t.n / V.n) - t step, on the unit
 * frame (u, v), times uv_per_world. n the surface's unit normal, t the
 * hair's unit tangent, V the unit direction from the eye, `step` the
 * hair's length between two shells (world units). Written to gap[0..1];
 * gap[2] is the second read's weight: 1 where the surface is seen within
 * PELT__SHELL_GAP_FULL of edge-on (|V.n|), 0 from PELT__SHELL_GAP_NONE
 * (smoothstep between): seen closer to face-on, the shells' counting of
 * a hair (pelt__lod_shell_overcount) already stands for it, and reading
 * the gap there made the torus 15% brighter than its hairs. Mirrors
 * shell_gap() in gl/shaders/shell_lod.glsl. */
#define PELT__SHELL_GAP_FULL 0.15f
#define PELT__SHELL_GAP_NONE 0.35f
#define PELT__SHELL_GAP_MIN_COS 0.05f
/* ... and not at the silhouette itself: the gap is worked out on the
 * shell's tangent plane, and where the eye grazes the surface (|V.n| below
 * PELT__SHELL_GAP_OUTLINE_FULL, none below _NONE) the surface curves away
 * before the ray meets the next shell: read there, the union drew hair
 * outside the shells' outline (test_fins_render's band). */
#define PELT__SHELL_GAP_OUTLINE_NONE 0.1f
#define PELT__SHELL_GAP_OUTLINE_FULL 0.2f
/* ... and only where the shells stand apart on screen: `spacing_px`, their
 * spacing seen side-on (negative: not known, no gate), weighs it from 0 at
 * PELT__SHELL_GAP_PX_NONE to 1 at PELT__SHELL_GAP_PX_FULL (smoothstep).
 * Closer, their sections overlap on screen and there are no beads; read
 * there anyway, the reference torus's silhouette widened into a pale band
 * (an independent look) and the CGAL bunny's frame took 1.10x. */
#define PELT__SHELL_GAP_PX_NONE 0.25f
#define PELT__SHELL_GAP_PX_FULL 0.6f
void pelt__lod_shell_gap(const float n[3], const float t[3], const float V[3], const float u[3], const float v[3],
                         float step, float uv_per_world, float spacing_px, float gap[3]);

/* The least count at a vertex whose surface the eye sees at n_dot_v
 * (lod.edge_depth): 1 / depth edge-on, rising smoothly (smoothstep) to 1
 * at |n_dot_v| = PELT__SHELL_EDGE_REACH. Seen edge-on, a ray crosses each
 * hair between two shells, in less than one spacing, and the hairs, seen
 * from the side, cover it over their length where a shell holds their
 * cross-sections once: the outer shells above the outline of a lip drew a
 * pale, see-through band where the hairs show a line of tips
 * (docs/reference.md, The near lip). 1 leaves every count at least 1.
 * Mirrors shell_edge_least() in gl/shaders/shell_lod.glsl. */
#define PELT__SHELL_EDGE_REACH 0.7f
float pelt__lod_shell_edge_least(float n_dot_v, float depth);

/* The cap on k for `layers` layers: at least PELT__SHELL_OVERCOUNT_MAX
 * shells, and as many as lie within PELT__SHELL_OVERCOUNT_REACH of the
 * fur's length. The ray leaves the hair after a height of the fur, not a
 * number of shells: with the cap held at 3 shells, 64 shells drew the fur
 * seen face-on brighter than 32 and 128 brighter still, where the hairs
 * stay as they are (docs/reference.md, The shells' count of a hair follows
 * the layers). Mirrors shell_overcount_cap(). */
#define PELT__SHELL_OVERCOUNT_MAX 3.0f
#define PELT__SHELL_OVERCOUNT_REACH (3.0f / 32.0f)
float pelt__lod_shell_overcount_cap(float layers);

/* A shell's coverage when k shells show the same hair: 1 - (1 - a)^(1/k),
 * so that the k composite to a. Mirrors shell_overcount_alpha(). */
float pelt__lod_shell_overcount_alpha(float a, float k);

/* A shell fragment's coverage in the form that composes its powers: the
 * overcount's share (above), a tuft's squeeze (pelt__clump_coverage) and a
 * layer's sub shells (pelt__sub_shell_alpha) are each 1 - (1 - a)^e, so
 * together 1 - (1 - a)^(e1 e2 e3): log2(1 - a) once (pelt__lod_coverage_log;
 * an opaque hair's is -1e30, which any positive exponent keeps opaque) and
 * pelt__lod_coverage_share(log, e1 e2 e3) once.
 * Mirror coverage_log() and coverage_share() in shell_lod.glsl. */
float pelt__lod_coverage_log(float a);
/* log2(1 - 0.05): a coverage below 0.05 draws no hair. Mirrors COVERAGE_CLEAR_LOG. */
#define PELT__COVERAGE_CLEAR_LOG (-0.0740005814f)
float pelt__lod_coverage_share(float clear_log, float e);

/* The hair's width over the layer spacing at height h: its root width
 * `width` (world units) tapered by `taper` towards the tip (h standing in
 * for the share of its length), over the spacing length / layers. Mirrors
 * shell_hair_span(). */
float pelt__lod_shell_hair_span(float width, float taper, float h, float layers, float length);

/* How far a hair drifts sideways from one shell to the next, per layer
 * spacing: a ringlet of radius ringlet (world units at the tip, 0 for
 * none; Silva's Eq. 4 helix, omega its frequency) at height h of hair
 * `length`, and the fur texture's own curl, its radius over the fur's
 * length times its angular frequency (0 for none). Mirrors
 * shell_hair_drift(). */
float pelt__lod_shell_hair_drift(float ringlet, float omega, float h, float length, float curl_radius,
                                 float curl_omega);

/* How far a leaning hair moves sideways from one shell to the next, per
 * layer spacing: tan of the angle between its tangent t and the surface
 * normal n (neither need be unit), |t x n| / |t . n|, at most
 * 1 / PELT__SHELL_LEAN_MIN_COS for a hair lying on the skin. Combing,
 * Silva's curl and the dynamics' bend all lean it; seen face-on, its
 * sections in consecutive shells stand that far apart, so the view's
 * budget weighs it with the curl's drift (shell_vs.glsl; docs/lod.md,
 * The view's shell budget). Mirrors shell_lean_drift(). */
#define PELT__SHELL_LEAN_MIN_COS 0.05f
float pelt__lod_shell_lean_drift(const float t[3], const float n[3]);

/* An even shell's premultiplied texel under weight w: over itself,
 * rgba (1 + w (1 - a)). Mirrors shell_view_texel() (shell_lod.glsl). */
void pelt__lod_view_texel(float w, float rgba[4]);

/* Writes the coarser levels' slices (pelt__lod_shell_extra_slices of
 * size x size RGBA8, premultiplied) from the volume's N + 1 slices. */
void pelt__lod_shell_composite(const uint8_t *volume, unsigned size, unsigned layers, uint8_t *extra);

/* The shell level for fur `fur_pixels` long on screen: the finest whose
 * spacing (fur_pixels 2^k / N) is at least `shell_pixels`. Its upper half
 * octave blends towards the next level (*blend from 0 to 1), so the count
 * of shells never jumps. Not finite or non-positive fur_pixels: level 0. */
void pelt__lod_shell_choice(unsigned layers, float fur_pixels, float shell_pixels, unsigned *level,
                            float *blend);

#endif
