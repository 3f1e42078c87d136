// All shells in one instanced draw: the layer is gl_InstanceID (plus
// u_instance_base where wet and dry are drawn apart, a layer at a time).
// Silva et al. Eq. 1: offset(h) = beta(h) + phi(h), sheared by the comb and
// the groom (Lengyel et al. §3): the groom's length scale s shortens the
// whole strand (its rest length, bent tip and curl radius), its lean adds
// to the comb's shear.
layout(location = PELT_ATTR_POSITION) in vec3 a_position;
layout(location = PELT_ATTR_NORMAL) in vec3 a_normal;
layout(location = PELT_ATTR_UV) in vec2 a_uv;
layout(location = PELT_ATTR_FUR_UV) in vec2 a_fur_uv;
layout(location = PELT_ATTR_TANGENT) in vec4 a_tangent;
layout(location = PELT_ATTR_TIP) in vec3 a_tip;     // p - p_root, mesh-local
layout(location = PELT_ATTR_COMB) in vec3 a_comb;    // comb direction x weight (0: stands up)
layout(location = PELT_ATTR_GROOM) in vec4 a_groom;  // lean u, lean v, length scale, density
layout(location = PELT_ATTR_HAIR_COLOR) in vec4 a_hair_color; // rgb, weight over u_color
layout(location = PELT_ATTR_FIT_NORMAL) in vec3 a_fit_normal; // the level's fitted normal less the vertex's, in (u, v, n)

// The shell pass's own: which shells this draw covers (Lengyel §2.4 level
// of detail, shell_lod.glsl).
uniform vec4 u_shells;     // x: shells from the first to the outermost, y: step 2^k,
                           // z: slice of instance 0, w: blend towards the next level
uniform vec2 u_shells_next; // the next level: x: its first slice, y: its shell count
uniform vec2 u_shell_view;  // the view's budget (shell_view_blend): x: the level's spacing
                            // side-on in pixels times clip w, per unit of groom length
                            // (0: off), y: the spacing it aims at, pixels
uniform float u_instance_base; // the instance of this draw's first shell (0 but in the wet split)
uniform float u_sub_shells;  // sub shells drawn for each layer (lod.sub_shells, pelt__clump_sub_shells; 0, 1: none)
uniform vec2 u_sub_view;     // close-up sub shells per vertex (sub_shell_need): x: the level's spacing
                             // side-on as u_shell_view.x (0: needed everywhere), y: 1 where the
                             // draw's count is the close-up one (a wet tuft's own: needed everywhere)
uniform float u_back_reach; // back-facing shells drawn only within the fur's reach of the
                            // silhouette: where N.V >= -u_back_reach (negative: everywhere)
uniform sampler2D u_mask;               // PELT_UNIT_MASK: wetness, rho in alpha

// The lean shader (docs/lod.md): what varies slowly over a triangle is
// worked out here, per vertex, so the fragment stage fetches and blends.
out vec2 v_uv;
out vec2 v_fur_uv;
out float v_h;
out float v_density;
out vec3 v_root;        // the groomed root and tip colours, lit: times
out vec3 v_tip;         // fur_light_terms' mul
out float v_spec;       // fur_light_terms' specular weight
out vec2 v_shadow_step; // Kenwright's step towards the light, fur tiles
#if defined(PELT_INTER_SHADOW) && !defined(PELT_LIGHT_PASS)
out float v_shadow_fade; // how much of Kenwright's shadow this shell draws (inter_shadow_view_fade)
#endif
flat out float v_clump_profile; // the tuft's profile f(h) (Eq. 5 above its base), the same for the whole layer
flat out vec3 v_slices; // slice, next level's slice, the blend towards it
out float v_sub_e;      // the sub shell's exponent in its layer's coverage (sub_shell_exponent)
#if (defined(PELT_WET) || defined(PELT_RINGLETS)) && !defined(PELT_LIGHT_PASS)
// A tuft's or a ringlet's own light (docs/wetness.md, Tuft light;
// docs/method.md, Ringlets): what the fragment stage needs to light the
// hair along its own tangent.
out vec2 v_light;       // fur_light_terms' facing and gamma
#endif
#if defined(PELT_RINGLETS) && !defined(PELT_LIGHT_PASS)
// A ringlet's, from dots: the hair's frame (unit tangent t, the surface's
// u and v, world) dotted with the light, with the eye's direction and with
// itself, for ringlet_dots.
out vec3 v_ring_l;      // (t.L, u.L, v.L)
out vec3 v_ring_e;      // (t.E, u.E, v.E)
out vec3 v_ring_g;      // (t.u, t.v, u.v)
#endif
#if defined(PELT_TUFTS) && !defined(PELT_LIGHT_PASS)
// A tuft's, from dots (a tuft bends the hair towards its centre; tuft_dots):
// the hair's unit tangent t and the world vectors du, dv of one mask-uv
// unit over the hair's length (along the tangent frame's u and v), dotted
// with the direction towards the light L, the eye's E and each other.
out vec3 v_tuft_l;      // (t.L, du.L, dv.L)
out vec3 v_tuft_e;      // (t.E, du.E, dv.E)
out vec4 v_tuft_g;      // (t.du, t.dv, du.du, dv.dv)
out float v_tuft_m;     // du.dv
flat out float v_clump_slope; // clump_tuft_slope(h): the same for the whole layer
#endif
out float v_alpha;      // the shell's opacity: fades as its level leaves, and
                        // where the view's budget leaves it out (face-on)
out float v_view;       // the view's budget: how far an even shell stands for two
#ifndef PELT_LIGHT_PASS
out vec3 v_gap;         // shell_gap: the gap to the next shell's section of the hair (fur tiles), its read's weight
#endif
out float v_aniso;      // fur_texture_aniso: texels of the footprint's long side to a pixel
out float v_overcount;  // shell_overcount: shells a ray of sight crosses inside one hair
uniform int u_no_overcount; // pelt_draw_desc.debug.no_overcount: each shell whole
uniform float u_fur_aniso;  // lod.texture_aniso: the most texels of a footprint's long side to a pixel
uniform float u_edge_depth; // lod.edge_depth: a shell seen edge-on stands for up to this many
#ifdef PELT_LIGHT_PASS
out float v_light_depth; // the light pass (gl/shadow_pass.c): depth from the light
#endif

void main()
{
    vec3 position = a_position, normal = a_normal;
    vec4 tangent = a_tangent;
#ifdef PELT_GPU_SKIN
    skin_vertex(position, normal, tangent);
#endif
    vec3 n = normalize(normal);
    float instance = float(gl_InstanceID) + u_instance_base;
    // A layer's shells are k sub shells below it, instances k i .. k i + k - 1:
    // close up, where the layers stand far apart on screen (docs/lod.md), and
    // where a tuft gathers its hairs (docs/wetness.md, Sub shells).
    float sub = max(u_sub_shells, 1.0);
    float part = mod(float(gl_InstanceID), sub);
    instance = floor((float(gl_InstanceID) + 0.5) / sub) + u_instance_base;
    float layer = shell_instance(instance, u_shells, u_shells_next, u_layers, v_slices, v_alpha);
    layer = sub_shell_layer(layer, part, sub, u_shells.y);
    v_view = 0.0;
    v_aniso = 1.0;
#ifndef PELT_LIGHT_PASS
    vec3 root = (u_model * vec4(position, 1.0)).xyz;
    float n_dot_v = dot(normalize(mat3(u_model) * n), normalize(u_eye - root));
#endif
    float h = (1.0 + layer) / u_layers;
    vec3 u = normalize(tangent.xyz);
    vec3 v = cross(n, u) * tangent.w;
    float rho = 0.0; // wetness straightens the curl; a dry frame reads no mask
#ifdef PELT_WET
    rho = textureLod(u_mask, a_uv, 0.0).a;
    fur_wetness = rho; // wet fur shines (fur_light_terms)
#endif
    float s = a_groom.z;
    float L = u_length * s;
    vec3 tip = a_tip * s;
    // On a coarse level the hair stands along the level's fitted normal,
    // its tip moved with it (docs/lod.md, The coarse levels' normals).
    vec3 fitted = level_fit_normal(n, u, v, a_fit_normal);
    tip += (fitted - n) * L;
    n = fitted;
    float K = u_curl_radius * s;
    vec3 shear = fur_groom_shear(a_comb, wet_slant(u_slant, u_wet_lie, rho), u, v, a_groom.xy);
    vec3 offset = fur_bend(n, L, tip, h)
                + fur_curl(u, v, u_curl_frequency, K, rho, h)
                + fur_comb(shear, L, 1.0, h);
    vec3 t = fur_tangent_combed(n, L, tip, u, v, shear, u_curl_frequency, K, rho, 1.0, h);
    vec4 world = u_model * vec4(position + offset, 1.0);
    vec3 world_t = normalize(mat3(u_model) * t); // the hair's unit tangent, world
    // Seen along its length, a hair shows in several shells: each takes
    // its share (docs/reference.md, The shells count a hair's edge once).
    // Water takes the ringlet out.
    float drift = shell_hair_drift((1.0 - rho) * u_ringlet_radius, u_curl_frequency, h, L, u_strand_curl_radius,
                                   u_strand_curl_omega);
    // Close up, the sub shells a vertex needs: where its fur is seen face-on
    // the layers stand close and the ones below the layer fade (docs/lod.md).
    float need = 1.0;
    float spacing_px = -1.0; // the shells' spacing side-on on screen, sub shells counted (-1: not known)
#ifndef PELT_LIGHT_PASS
    float w_clip = max((u_view_proj * vec4(root, 1.0)).w, 1e-6); // the root's: spacings on screen
    if (sub > 1.0 && u_sub_view.x > 0.0 && u_sub_view.y > 0.5)
        need = sub_shell_need(u_sub_view.x * a_groom.z / w_clip, n_dot_v, drift);
#endif
    v_sub_e = sub_shell_exponent(part, sub, need);
#ifndef PELT_LIGHT_PASS
    if (u_shell_view.x > 0.0) {
        // Face-on, the shells' spacing is foreshortened: the odd shells
        // (from the outside) fade and the even ones stand for them, unless
        // the hair curls, moving sideways from one shell to the next.
        // A leaning hair (combed, curled, bent) moves sideways too: face-on
        // its sections would stand twice as far apart with every other shell.
        float view_drift = length(vec2(drift, shell_lean_drift(t, n)));
        float w = shell_view_blend(u_shell_view.x * a_groom.z / w_clip, n_dot_v, u_shell_view.y, view_drift);
        bool odd = mod(u_shells.x - 1.0 - instance, 2.0) > 0.5;
        v_alpha *= odd ? 1.0 - w : 1.0;
        v_view = odd ? 0.0 : w;
        // Sharp across a grazing view, unless the shells stand far enough
        // apart on screen to show as rows (docs/shading.md): the sub
        // shells stand closer.
        spacing_px = u_shell_view.x * a_groom.z / w_clip / (1.0 + (sub - 1.0) * need);
        v_aniso = fur_texture_aniso(spacing_px, n_dot_v,
                                    u_fur_aniso);
    }
#endif
    // Seen edge-on, a ray crosses a hair in less than one shell spacing and
    // the hairs cover it over their length: the shell may count for more
    // than one crossing (lod.edge_depth; docs/reference.md, The near lip).
#ifdef PELT_LIGHT_PASS
    float least = 1.0;
#else
    float least = shell_edge_least(n_dot_v, u_edge_depth);
#endif
    // The ray's drift against the hair from one shell to the next (docs/
    // reference.md, A leaning hair in the shells' stack).
    vec3 to_eye = normalize(u_eye - world.xyz);
    float cos_view = shell_stack_cos(world_t, to_eye, normalize(mat3(u_model) * n));
    v_overcount = u_no_overcount != 0 ? 1.0
                : shell_overcount(shell_hair_span(u_hair_width, u_taper, h, u_layers, L), cos_view, drift, least,
                                  shell_overcount_cap(u_layers));
#if !defined(PELT_LIGHT_PASS) && defined(PELT_NO_GAP)
    v_gap = vec3(0.0); // a face-on triangle of the view split: no read across the gap
#elif !defined(PELT_LIGHT_PASS)
    // Seen from the side, a hair between this shell and the next one down
    // (docs/reference.md, Hairs seen from the side, not beads).
    float scale = length(mat3(u_model) * u); // the model's, uniform
    v_gap = shell_gap(normalize(mat3(u_model) * n), world_t, normalize(world.xyz - u_eye),
                      normalize(mat3(u_model) * u), normalize(mat3(u_model) * v), L * scale / (u_layers * sub),
                      u_tiling / scale, spacing_px);
#endif
    vec3 light_mul = vec3(1.0);
#ifdef PELT_LIGHT_PASS
    // Drawn from the light into its opacity slices: no lighting.
    vec3 lc = shadow_coord(world.xyz);
    v_light_depth = lc.z;
    gl_Position = vec4(lc * 2.0 - 1.0, 1.0);
#else
    fur_light_terms(mat3(u_model) * t, mat3(u_model) * n, world.xyz, h, light_mul, v_spec);
#if defined(PELT_WET) || defined(PELT_RINGLETS)
    v_light = fur_light_reach.xz; // the reach the free hair was just lit with
#endif
#ifdef PELT_RINGLETS
    vec3 ring_t = world_t, ring_u = normalize(mat3(u_model) * u);
    vec3 ring_v = normalize(mat3(u_model) * v);
    ringlet_frame_dots(ring_t, ring_u, ring_v, normalize(u_light_dir), normalize(world.xyz - u_eye), v_ring_l,
                       v_ring_e, v_ring_g);
    light_mul = ringlet_light_mul(light_mul, fur_light_reach.z);
#endif
#ifdef PELT_TUFTS
    // The mask's uv runs along the fur uv, which tiles u_fur_per_uv tiles
    // per uv unit and u_tiling per world unit along the tangent frame.
    vec2 world_per_uv = u_fur_per_uv / (u_tiling * max(L, 1e-6));
    vec3 tuft_u = mat3(u_model) * u * world_per_uv.x, tuft_v = mat3(u_model) * v * world_per_uv.y;
    vec3 to_light = normalize(u_light_dir), from_eye = normalize(world.xyz - u_eye);
    v_tuft_l = vec3(dot(world_t, to_light), dot(tuft_u, to_light), dot(tuft_v, to_light));
    v_tuft_e = vec3(dot(world_t, from_eye), dot(tuft_u, from_eye), dot(tuft_v, from_eye));
    v_tuft_g = vec4(dot(world_t, tuft_u), dot(world_t, tuft_v), dot(tuft_u, tuft_u), dot(tuft_v, tuft_v));
    v_tuft_m = dot(tuft_u, tuft_v);
    v_clump_slope = clump_tuft_slope(h, u_clump_blend, u_layers);
#endif
#ifdef PELT_INTER_SHADOW
    v_shadow_fade = inter_shadow_view_fade(n_dot_v);
#endif
    v_shadow_step = inter_shadow_offset(normalize(u_light_dir), normalize(mat3(u_model) * u),
                                        normalize(mat3(u_model) * v), u_inter_shadow_step);
    gl_Position = u_view_proj * world;
    // Far round the back the skin hides the fur: the vertex goes beyond the
    // far plane where it stands (its triangles clip away there; a triangle
    // reaching towards the silhouette keeps its part on this side).
    if (shell_back_hidden(n_dot_v, u_back_reach)) gl_Position.z = 2.0 * abs(gl_Position.w);
#endif
#ifndef GL_ES
    // Where the shell has faded out (the view's budget face-on, a level
    // leaving) it is clipped before rasterising: the clip distance is the
    // opacity the fragment stage discards below, interpolated as it is, so
    // the same fragments go, but they cost no shading. (WebGL2 has no
    // gl_ClipDistance: there they are discarded.)
    // A sub shell below its layer that the vertex does not need goes too.
    gl_ClipDistance[0] = min(v_alpha, part < sub - 1.5 ? need : 1.0) - 1.0 / 255.0;
#endif
    v_root = groom_root_color(u_color, a_hair_color) * light_mul;
    v_tip = groom_tip_color(u_color, u_tip_color, a_hair_color) * light_mul;
    v_uv = a_uv;
    v_fur_uv = a_fur_uv;
    v_h = h;
    v_density = a_groom.w;
    v_clump_profile = clump_tuft_profile(h, u_clump_blend, u_layers);
}
