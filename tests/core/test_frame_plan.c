/* The frame plan (core/fur/frame_plan.c) without GL: levels of detail
 * follow the distance, the light's frame holds the fur, the ground lies
 * under the mesh, the shader's features and the passes follow the fur and
 * the switches. */
#include "support/check.h"

#include "core/fur/frame_plan.h"
#include "core/fur/fur_gpu.h"
#include "core/fur/lod.h"
#include "pelt/camera.h"
#include "pelt/fur.h"
#include "pelt/mesh.h"
#include "pelt/wetness.h"

#include <math.h>
#include <string.h>

static const pelt__frame_switches everything = {.skin = true, .fins = true, .shells = true, .inter_shadow = true,
                                                .shadows = true, .sub_shells = true};

static pelt_view view_at(float distance)
{
    pelt_camera cam = {35.0f, 25.0f, distance, 40.0f, {0, 0, 0}}; /* degrees */
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(&cam, 4.0f / 3.0f, &v);
    v.width = 800, v.height = 600;
    v.light.direction[0] = 0.3f, v.light.direction[1] = 1.0f, v.light.direction[2] = 0.5f;
    return v;
}

static pelt__frame_setup setup_with(bool shadows, bool ground)
{
    pelt__frame_setup s;
    memset(&s, 0, sizeof s);
    s.shadow.enabled = shadows;
    s.shadow.map_size = 512, s.shadow.slices = 4, s.shadow.softness = 1.0f, s.shadow.depth = 1.0f;
    s.shadow.density = 1.0f;
    s.shadow_map_size = shadows ? 512 : 0;
    s.ground.enabled = ground, s.ground.size = 3.0f;
    return s;
}

/* Runs a test on fur of desc d over a 48 x 24 torus. */
static void on_torus(pelt_fur_desc d, void (*test)(pelt_fur *fur, const pelt_mesh *m))
{
    pelt_mesh *m = NULL;
    pelt_fur *fur = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 48, 24, &m, NULL) == PELT_OK);
    CHECK(m && pelt_fur_create(m, &d, &fur, NULL) == PELT_OK);
    if (fur) test(fur, m);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

/* Further away, the fur is shorter on screen: the shell level never gets
 * finer and ends coarser; the mesh level likewise. */
static void levels_of_detail_follow_the_distance(pelt_fur *fur, const pelt_mesh *m)
{
    (void)m;
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    unsigned last_shell = 0, last_mesh = 0;
    pelt__frame_plan p;
    for (int i = 0; i < 8; i++) {
        pelt_view v = view_at(3.0f * powf(2.0f, (float)i));
        pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
        CHECK(!p.lod.full_mesh);
        CHECK(p.lod.shell_level >= last_shell && p.lod.mesh_level >= last_mesh);
        last_shell = p.lod.shell_level, last_mesh = p.lod.mesh_level;
        printf("  distance %6.1f: shell level %u, mesh level %u\n", 3.0 * pow(2.0, i), p.lod.shell_level, p.lod.mesh_level);
    }
    CHECK(last_shell >= 3); /* 32 shells a few pixels deep come down to 4 or fewer */
    CHECK(last_mesh > 0);
    pelt_view near = view_at(3.0f);
    pelt__frame_plan_make(fur, &near, &everything, &setup, &cache, &p);
    CHECK(p.lod.shell_level == 0);
    /* Inspecting a range of layers keeps the finest shells at any distance. */
    pelt__frame_switches one = everything;
    one.one_height = true;
    pelt_view far = view_at(400.0f);
    pelt__frame_plan_make(fur, &far, &one, &setup, &cache, &p);
    CHECK(p.lod.shell_level == 0 && p.lod.shell_blend == 0.0f);
}

/* The view's shell budget: on near (a finer level than the coarsest is
 * drawn); it carries the level's
 * side-on spacing times clip w (the same at any distance for one level:
 * divided by each vertex's clip w in the shader, so the plan's figure does
 * not change with the distance); off when measuring flat shells, when a
 * range of layers is inspected and at the coarsest level. */
static void the_view_budget_follows_the_view(pelt_fur *fur, const pelt_mesh *m)
{
    (void)m;
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    pelt__frame_plan p, q;
    pelt_view near = view_at(3.0f), nearer = view_at(1.5f);
    pelt__frame_plan_make(fur, &near, &everything, &setup, &cache, &p);
    CHECK(p.lod.shell_level == 0 && p.lod.shell_view[0] > 0.0f);
    CHECK(p.lod.shell_view[1] == pelt_fur_get_desc(fur).lod.shell_pixels);
    CHECK(!(p.shell_features & PELT__SHELL_LOD_BLEND)); /* no second fetch for it */
    pelt__frame_plan_make(fur, &nearer, &everything, &setup, &cache, &q);
    if (q.lod.shell_level == p.lod.shell_level)
        CHECK_NEAR(q.lod.shell_view[0], p.lod.shell_view[0], 1e-4f * p.lod.shell_view[0]);
    pelt__frame_switches sw = everything;
    sw.flat_shells = true;
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(p.lod.shell_view[0] == 0.0f);
    sw = everything;
    sw.one_height = true;
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(p.lod.shell_view[0] == 0.0f);
    pelt_view far = view_at(3000.0f);
    pelt__frame_plan_make(fur, &far, &everything, &setup, &cache, &p);
    CHECK(p.lod.shell_level + 1 == pelt__lod_shell_levels(pelt_fur_get_desc(fur).layers));
    CHECK(p.lod.shell_view[0] == 0.0f);
}

/* The light's maps run only when they are on, made and not switched off;
 * then every point of the fur's reach projects inside the maps. */
static void the_light_frame_holds_the_fur(pelt_fur *fur, const pelt_mesh *m)
{
    pelt__ground_cache cache = {0};
    pelt_view v = view_at(5.0f);
    pelt__frame_plan p;
    pelt__frame_setup off = setup_with(false, false), on = setup_with(true, false);
    pelt__frame_plan_make(fur, &v, &everything, &off, &cache, &p);
    CHECK(!p.light_maps && !(p.shell_features & PELT__SHELL_SHADOW_MAP));
    pelt__frame_setup unmade = on;
    unmade.shadow_map_size = 0;
    pelt__frame_plan_make(fur, &v, &everything, &unmade, &cache, &p);
    CHECK(!p.light_maps);
    pelt__frame_switches no_shadows = everything;
    no_shadows.shadows = false;
    pelt__frame_plan_make(fur, &v, &no_shadows, &on, &cache, &p);
    CHECK(!p.light_maps);
    pelt__frame_plan_make(fur, &v, &everything, &on, &cache, &p);
    CHECK(p.light_maps && (p.shell_features & PELT__SHELL_SHADOW_MAP));
    CHECK(p.shadow.map[1] == 4.0f && p.light_pass.shell_level > 0);
    /* Every vertex pushed out by the fur's length lands in [0,1]^2. */
    const pelt_mesh_data md = pelt_mesh_get_data(m);
    const float len = pelt_fur_get_desc(fur).length;
    size_t outside = 0;
    for (size_t i = 0; i < md.vertex_count; i++) {
        float q[3];
        for (int k = 0; k < 3; k++) q[k] = md.positions[3 * i + k] + len * md.normals[3 * i + k];
        const float *L = p.shadow.light_matrix;
        float s = L[0] * q[0] + L[4] * q[1] + L[8] * q[2] + L[12];
        float t = L[1] * q[0] + L[5] * q[1] + L[9] * q[2] + L[13];
        float dd = L[2] * q[0] + L[6] * q[1] + L[10] * q[2] + L[14];
        if (!(s >= 0.0f && s <= 1.0f && t >= 0.0f && t <= 1.0f && dd >= 0.0f && dd <= 1.0f)) outside++;
    }
    CHECK(outside == 0);
}

/* The ground disc lies at the mesh's lowest point under its centre; a
 * lifted model lifts it. */
static void the_ground_lies_under_the_mesh(pelt_fur *fur, const pelt_mesh *m)
{
    (void)m;
    pelt__ground_cache cache = {0};
    pelt_view v = view_at(5.0f);
    const pelt__frame_setup setup = setup_with(false, true), none = setup_with(false, false);
    pelt__frame_plan p;
    pelt__frame_plan_make(fur, &v, &everything, &none, &cache, &p);
    CHECK(!p.ground);
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    CHECK(p.ground);
    CHECK_NEAR(p.disc[1], -0.4, 1e-5); /* the torus's tube radius below its plane */
    CHECK_NEAR(p.disc[0], 0.0, 1e-5);
    CHECK(p.disc[3] > 3.0f);
    v.model[13] = 2.0f;
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    CHECK_NEAR(p.disc[1], 1.6, 1e-5);
}

/* The shader's features and the passes follow the fur and the switches. */
static void features_and_passes_follow_the_switches(pelt_fur *fur, const pelt_mesh *m)
{
    (void)m;
    const pelt__frame_setup setup = setup_with(false, false);
    pelt_view v = view_at(5.0f);
    pelt__ground_cache cache = {0};
    pelt__frame_plan p;
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    CHECK(p.skin && p.fins && p.shells && !p.gpu_skin);
    CHECK(p.shell_features & PELT__SHELL_INTER_SHADOW);
    /* Each hair model builds its own variant: Kajiya-Kay and the table their
       bit, Scheuermann-Marschner neither (gl/shaders/fur_light.glsl). */
    const unsigned models = PELT__SHELL_KAJIYA_KAY | PELT__SHELL_LIGHT_TABLE;
    const unsigned model_bits[] = {PELT__SHELL_KAJIYA_KAY, PELT__SHELL_LIGHT_TABLE, 0};
    CHECK((p.shell_features & models) == model_bits[pelt_fur_get_desc(fur).look.shading]);
    CHECK(!(p.shell_features & (PELT__SHELL_WET | PELT__SHELL_COLOR_TEXTURE)));
    CHECK(p.lod.cull); /* a closed torus with fins: the back shells go */
    pelt__frame_switches sw = everything;
    sw.inter_shadow = false, sw.fins = false, sw.skin = false, sw.gpu_skin = true;
    pelt__frame_plan_make(fur, &v, &sw, &setup, &cache, &p);
    CHECK(!(p.shell_features & PELT__SHELL_INTER_SHADOW));
    CHECK(!p.fins && !p.skin && p.shells);
    CHECK(!p.gpu_skin); /* the torus has no bones */
    CHECK(!p.lod.cull); /* without fins nothing carries the silhouette */
    sw.cull_shells = 1;
    pelt__frame_plan_make(fur, &v, &sw, &setup, &cache, &p);
    CHECK(p.lod.cull);
    /* Water makes the wet variant. */
    pelt_droplet drop = {{0.5f, 0.5f}, 0.2f, 1.0f};
    CHECK(pelt_fur_add_droplet(fur, &drop, NULL) == PELT_OK);
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    CHECK(p.shell_features & PELT__SHELL_WET);
    CHECK(p.light_pass.features == 0); /* no light pass this frame */
}

static void run_levels_of_detail_follow_the_distance(void) { on_torus((pelt_fur_desc){.layers = 32, .look.texture_size = 32}, levels_of_detail_follow_the_distance); }
static void run_the_light_frame_holds_the_fur(void) { on_torus((pelt_fur_desc){.look.texture_size = 32}, the_light_frame_holds_the_fur); }
static void run_the_ground_lies_under_the_mesh(void) { on_torus((pelt_fur_desc){.look.texture_size = 32}, the_ground_lies_under_the_mesh); }
static void run_features_and_passes_follow_the_switches(void)
{
    const pelt_shading_model models[] = {PELT_SHADING_KAJIYA_KAY, PELT_SHADING_LENGYEL_TABLE, PELT_SHADING_MARSCHNER};
    for (int k = 0; k < 3; k++)
        on_torus((pelt_fur_desc){.look.texture_size = 32, .look.inter_shadow = true, .look.shading = models[k]},
                 features_and_passes_follow_the_switches);
}

/* The silhouette of a closed mesh: with the fins, the back-facing shells
 * are culled; without them they are drawn within the fur's reach of the
 * outline (pelt__lod_back_hidden leaves out the vertices further round). */
static void back_shells_carry_the_silhouette_without_fins(pelt_fur *fur, const pelt_mesh *m)
{
    (void)m;
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    pelt__frame_plan p;
    pelt_view near = view_at(3.0f);
    pelt__frame_plan_make(fur, &near, &everything, &setup, &cache, &p);
    CHECK(p.lod.cull && p.lod.back_reach < 0.0f);
    pelt__frame_switches sw = everything;
    sw.fins = false;
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach == pelt_fur_get_desc(fur).lod.back_reach);
    CHECK(pelt__lod_back_hidden(-0.5f, p.lod.back_reach) && !pelt__lod_back_hidden(-0.1f, p.lod.back_reach));
    CHECK(!pelt__lod_back_hidden(0.5f, p.lod.back_reach) && !pelt__lod_back_hidden(-0.9f, -1.0f));
    sw.cull_shells = -1; /* never culled: every back-facing shell */
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach < 0.0f);
}

/* An open mesh (a subdivided square): nothing is culled whole, since
 * there is no front to hide the back; but each back-facing patch's own skin
 * (drawn on both sides) hides its fur, which grows away from the eye, so
 * the shells far round the back are left out, with fins or without, as
 * long as the skin is drawn. */
static void open_mesh_leaves_out_the_shells_behind_their_skin(void)
{
    pelt_mesh *m = NULL;
    pelt_fur *fur = NULL;
    CHECK(pelt_mesh_square(2.0f, 24, &m, NULL) == PELT_OK);
    pelt_fur_desc d = {.look.texture_size = 32};
    CHECK(m && pelt_fur_create(m, &d, &fur, NULL) == PELT_OK);
    if (!fur) {
        pelt_mesh_destroy(m);
        return;
    }
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    pelt__frame_plan p;
    pelt_view near = view_at(3.0f);
    const float reach = pelt_fur_get_desc(fur).lod.back_reach;
    pelt__frame_plan_make(fur, &near, &everything, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach == reach);
    pelt__frame_switches sw = everything;
    sw.fins = false;
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach == reach);
    sw.cull_shells = 1; /* pelt bench's "no fins": the same shells as with them */
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach == reach);
    sw = everything;
    sw.skin = false; /* nothing in front of the back's fur */
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach < 0.0f);
    sw = everything;
    sw.cull_shells = -1;
    pelt__frame_plan_make(fur, &near, &sw, &setup, &cache, &p);
    CHECK(!p.lod.cull && p.lod.back_reach < 0.0f);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

/* Sub shells (docs/wetness.md): a wet frame measures how far the tufts'
 * pull moves a hair at a mean tuft's rim, in pixels where the fur is seen
 * largest: at half the distance, more than twice as far (the nearest
 * vertex comes closer than half as near); the eye inside the torus's bounding sphere still gets a finite measure
 * from the vertices in view; none when dry, with the switch off, or when a
 * band of layers is inspected. */
static void tufts_sweep_follows_the_view(pelt_fur *fur, const pelt_mesh *m)
{
    (void)m;
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    pelt__frame_plan p;
    pelt_view v = view_at(6.0f);
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    CHECK(p.lod.tuft_pull[1] == 0.0f); /* dry */
    pelt_droplet drop = {{0.5f, 0.5f}, 0.3f, 1.0f};
    CHECK(pelt_fur_add_droplet(fur, &drop, NULL) == PELT_OK);
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    float far = p.lod.tuft_pull[1];
    v = view_at(3.0f);
    pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
    float near = p.lod.tuft_pull[1];
    const pelt_fur_desc d = pelt_fur_get_desc(fur);
    printf("  a tuft's rim sweeps %.1f px at distance 6, %.1f at 3 (clump size %.3f)\n", (double)far, (double)near,
           (double)d.wet.clump_size);
    CHECK(p.lod.tuft_pull[0] == d.wet.clump_blend);
    CHECK(far > 0.0f && near > 1.98f * far && near < 6.0f * far); /* its nearest point comes closer still */
    pelt_view inside = view_at(0.5f);
    pelt__frame_plan_make(fur, &inside, &everything, &setup, &cache, &p);
    printf("  from inside its bounding sphere: %.1f px\n", (double)p.lod.tuft_pull[1]);
    CHECK(isfinite(p.lod.tuft_pull[1]) && p.lod.tuft_pull[1] > near && p.lod.tuft_pull[1] <= 4.0f * 600.0f);
    pelt__frame_switches sw = everything;
    sw.sub_shells = false;
    pelt__frame_plan_make(fur, &v, &sw, &setup, &cache, &p);
    CHECK(p.lod.tuft_pull[1] == 0.0f);
    sw = everything;
    sw.one_height = true;
    pelt__frame_plan_make(fur, &v, &sw, &setup, &cache, &p);
    CHECK(p.lod.tuft_pull[1] == 0.0f);
}

/* Close up, every layer in sub shells (lod.sub_shells, docs/lod.md): one
 * a layer at the default framing's distance, more as the eye comes close
 * (the fur's nearest vertex in view sets the spacing, also from inside the
 * bounding sphere), never more than the cap; one with the cap at 1, the
 * switch off, or a band of layers inspected. Dry or wet alike. */
static void close_up_layers_in_sub_shells(pelt_fur *fur, const pelt_mesh *m)
{
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    pelt__frame_plan p;
    pelt_view v;
    unsigned was = 0;
    const float distances[] = {12.0f, 6.0f, 3.0f, 1.5f}; /* outside the bounding sphere, coming closer */
    for (size_t i = 0; i < sizeof distances / sizeof distances[0]; i++) {
        v = view_at(distances[i]);
        pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
        printf("  distance %4.1f: %u shells a layer\n", (double)distances[i], p.lod.sub_shells);
        CHECK(p.lod.sub_shells >= 1 && p.lod.sub_shells >= was && p.lod.sub_shells <= 4);
        if (i < 2) CHECK(p.lod.sub_shells == 1); /* the whole torus in view: one a layer */
        was = p.lod.sub_shells;
    }
    CHECK(was > 1);
    pelt_view inside = view_at(0.5f);
    pelt__frame_plan_make(fur, &inside, &everything, &setup, &cache, &p);
    printf("  from inside its bounding sphere: %u\n", p.lod.sub_shells);
    CHECK(p.lod.sub_shells > 1 && p.lod.sub_shells <= 4);
    pelt__frame_switches sw = everything;
    sw.sub_shells = false;
    pelt__frame_plan_make(fur, &v, &sw, &setup, &cache, &p);
    CHECK(p.lod.sub_shells == 1);
    sw = everything;
    sw.one_height = true;
    pelt__frame_plan_make(fur, &v, &sw, &setup, &cache, &p);
    CHECK(p.lod.sub_shells == 1);
    pelt_fur *one = NULL;
    CHECK(pelt_fur_create(m, &(pelt_fur_desc){.look.texture_size = 32, .lod.sub_shells = 1}, &one, NULL) == PELT_OK);
    if (one) pelt__frame_plan_make(one, &v, &everything, &setup, &cache, &p);
    CHECK(one && p.lod.sub_shells == 1);
    pelt_fur_destroy(one);
}

static void run_close_up_layers_in_sub_shells(void) { on_torus((pelt_fur_desc){.look.texture_size = 32}, close_up_layers_in_sub_shells); }
static void run_tufts_sweep_follows_the_view(void) { on_torus((pelt_fur_desc){.look.texture_size = 32}, tufts_sweep_follows_the_view); }
static void run_back_shells_carry_the_silhouette_without_fins(void) { on_torus((pelt_fur_desc){.look.texture_size = 32}, back_shells_carry_the_silhouette_without_fins); }
static void run_the_view_budget_follows_the_view(void) { on_torus((pelt_fur_desc){.layers = 32, .look.texture_size = 32}, the_view_budget_follows_the_view); }

/* The fins' level (pelt__lod_pick_fins): a dense mesh whose fins would
 * stand closer than the fin texture's slab draws them from a coarser level,
 * within the slab and the error bound; where the edges are longer than the
 * slab, the shells' own level. */
static void fins_stand_up_to_a_slab_apart(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 192, 96, &m, NULL) == PELT_OK);
    if (!m) return;
    const pelt__frame_setup setup = setup_with(false, false);
    pelt__ground_cache cache = {0};
    const unsigned densities[] = {8, 1}; /* slabs of 1/4 and 1/32 of a tile (the default is 1/16) */
    for (int k = 0; k < 2; k++) {
        pelt_fur *fur = NULL;
        pelt_fur_desc d = {.look.texture_size = 32, .fins.density = (float)densities[k]};
        CHECK(pelt_fur_create(m, &d, &fur, NULL) == PELT_OK);
        if (!fur) continue;
        pelt__fur_snapshot fs;
        pelt__fur_gpu_snapshot(fur, &fs);
        const pelt_fur_desc fd = pelt_fur_get_desc(fur);
        float slab = fd.fins.density / ((float)fd.look.texture_size * fd.look.tiling);
        pelt_view v = view_at(3.0f);
        pelt__frame_plan p;
        pelt__frame_plan_make(fur, &v, &everything, &setup, &cache, &p);
        const pelt__lod_level *fins = &fs.lod->levels[p.lod.fin_level];
        printf("  slab %.3f: mesh level %u (edge %.3f), fins from level %u (edge %.3f)\n", (double)slab,
               p.lod.mesh_level, (double)fs.lod->levels[p.lod.mesh_level].edge, p.lod.fin_level, (double)fins->edge);
        CHECK(p.lod.fin_level >= p.lod.mesh_level);
        if (p.lod.fin_level > p.lod.mesh_level) CHECK(fins->edge <= slab);
        if (k == 0) CHECK(p.lod.fin_level > p.lod.mesh_level);
        else CHECK(p.lod.fin_level == p.lod.mesh_level && fs.lod->levels[p.lod.mesh_level + 1].edge > slab);
        pelt_fur_destroy(fur);
    }
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(fins_stand_up_to_a_slab_apart);
    RUN(run_the_view_budget_follows_the_view);
    RUN(run_back_shells_carry_the_silhouette_without_fins);
    RUN(open_mesh_leaves_out_the_shells_behind_their_skin);
    RUN(run_levels_of_detail_follow_the_distance);
    RUN(run_the_light_frame_holds_the_fur);
    RUN(run_the_ground_lies_under_the_mesh);
    RUN(run_features_and_passes_follow_the_switches);
    RUN(run_tufts_sweep_follows_the_view);
    RUN(run_close_up_layers_in_sub_shells);
    return check_summary();
}
