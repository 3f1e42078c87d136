// Shell fragments: fur texture slice of this layer, lit by the terms the
// vertex stage worked out (Kajiya-Kay, Silva et al. Eq. 6) and folded into
// the root and tip colours, alpha discard.
in vec2 v_uv;
in vec2 v_fur_uv;
in float v_density;
in vec3 v_root; // lit
in vec3 v_tip;
in float v_spec;
in vec2 v_shadow_step;
#if defined(PELT_INTER_SHADOW) && !defined(PELT_LIGHT_PASS)
in float v_shadow_fade;
#endif
flat in float v_clump_profile; // clump_profile(h): constant per layer
flat in vec3 v_slices;
in float v_sub_e; // the sub shell's exponent in its layer's coverage (shell_vs.glsl)
in float v_alpha;
in float v_view;
#ifndef PELT_LIGHT_PASS
in vec3 v_gap;
#endif
in float v_aniso;
in float v_overcount; // shells a ray crosses inside one hair (shell_vs.glsl)
#if (defined(PELT_WET) || defined(PELT_RINGLETS)) && !defined(PELT_LIGHT_PASS)
in vec2 v_light;    // a tuft's or ringlet's own light (shell_vs.glsl)
#endif
#if defined(PELT_RINGLETS) && !defined(PELT_LIGHT_PASS)
in vec3 v_ring_l;   // a ringlet's, from dots
in vec3 v_ring_e;
in vec3 v_ring_g;
#endif
#if defined(PELT_TUFTS) && !defined(PELT_LIGHT_PASS)
in vec3 v_tuft_l;   // a tuft's, from dots (tuft_dots)
in vec3 v_tuft_e;
in vec4 v_tuft_g;
in float v_tuft_m;
flat in float v_clump_slope;
#endif
#if defined(PELT_RINGLETS) && !defined(PELT_LIGHT_PASS)
in float v_h;       // the shell's height over the full length
#endif

uniform highp sampler2DArray u_fur; // PELT_UNIT_FUR
uniform sampler2D u_color_tex;     // PELT_UNIT_COLOR
uniform sampler2D u_mask;          // PELT_UNIT_MASK
uniform int u_no_inter_shadow;     // the shell pass's own: 1 skips inter-fur shadows
#ifdef PELT_FUR_TAPS
uniform float u_fur_taps;          // lod.texture_taps: the most fetches of a hair
#endif

// A layer's coverage a, shared among the sub shells drawn for it.
float layer_share(float a)
{
    return coverage_share(coverage_log(a), v_sub_e);
}

// layer_share's exponent (coverage_share): this sub shell's share.
float layer_share_exponent()
{
    return v_sub_e;
}

#ifdef PELT_LIGHT_PASS
// The light pass (gl/shadow_pass.c): the fur's opacity into slices 0-3, 4-7.
in float v_light_depth;
layout(location = 0) out vec4 o_slices0;
layout(location = 1) out vec4 o_slices1;
#else
out vec4 o_color;
#endif

// The fur texture's mip level for this fragment (shell_fur_texture_lod) and the
// gain on its hairs' edges (fur_edge_gain): set first in main, from the fur
// uv's screen derivatives, before any discard.
float fur_lod = 0.0;
float fur_gain = 1.0;
// The fetches along the footprint's longer side (fur_texture_taps) and the
// step between them in fur uv: one fetch unless lod.texture_taps asks more.
float fur_taps = 1.0;
vec2 fur_step = vec2(0.0);

// One fetch of the hair of this shell at fur_uv, `offset` slices along the
// volume, blended into the next shell level where it fades.
vec4 shell_fetch(vec2 fur_uv, float offset)
{
    vec4 hair = textureLod(u_fur, vec3(fur_uv, v_slices.x + offset), fur_lod);
#ifdef PELT_LOD_BLEND
    hair = mix(hair, textureLod(u_fur, vec3(fur_uv, v_slices.y + offset), fur_lod), v_slices.z);
#endif
    return hair;
}

// The hair of this shell at fur_uv, `offset` slices along the volume (a
// ringlet level): fur_taps fetches across the footprint, averaged.
vec4 shell_hair(vec2 fur_uv, float offset)
{
#ifdef PELT_FUR_TAPS
    vec4 sum = vec4(0.0);
    vec2 at = fur_uv - fur_step * (0.5 * fur_taps - 0.5);
    for (float i = 0.0; i < fur_taps; i += 1.0) {
        sum += shell_fetch(at, offset);
        at += fur_step;
    }
    return sum / fur_taps;
#else
    return shell_fetch(fur_uv, offset);
#endif
}

// The hair at fur_uv under wetness rho: with ringlets, water takes the
// curl out, between the levels the volume holds it at (docs/method.md).
// Dry hair reads the full-curl level with weight 1: no branch, which
// llvmpipe would pay for on both sides. A dry frame reads it alone.
vec4 wet_hair(vec2 fur_uv, float rho)
{
#if defined(PELT_RINGLETS) && defined(PELT_WET)
    vec3 level = ringlet_levels(rho, u_ringlets.x, u_ringlets.y);
    return mix(shell_hair(fur_uv, level.x), shell_hair(fur_uv, level.y), level.z);
#else
    return shell_hair(fur_uv, 0.0);
#endif
}

#if defined(PELT_TUFTS) && !defined(PELT_LIGHT_PASS)
// The dots (T.L, T.E) of a tuft's hair along its tangent T in the tuft.
vec2 shell_tuft_dots(vec2 to_centre, float rho)
{
    return tuft_dots(v_tuft_l, v_tuft_e, v_tuft_g, v_tuft_m, to_centre, u_clump_tightness * rho * v_clump_slope);
}

// A tuft's hair lit along its tuft (own_light.glsl), the free hair's light
// from its dots.
void tuft_light(vec2 to_centre, float rho, inout vec3 base, inout float spec)
{
    own_light_dots(shell_tuft_dots(to_centre, rho), v_light, free_light_inverse_dots(v_tuft_l.x, v_tuft_e.x, rho, v_light),
                   rho, base, spec);
}
#endif

#if defined(PELT_RINGLETS) && !defined(PELT_LIGHT_PASS)
// The ringlet of the hair with this id at this shell's height.
void shell_ringlet_light(float id, float rho, inout vec3 base, inout float spec)
{
    ringlet_light(id, rho, v_h, v_light, v_ring_l, v_ring_e, v_ring_g, base, spec);
}

// The id of the hair this pixel shows, read at the fur texture's finest
// level (docs/method.md, Ringlets): where the coverage is read coarser,
// its texel's id is one hair's (pelt__fur_gpu_mip_down), but the bilinear
// read blends up to four texels' ids and neighbouring pixels share them
// (Silva Fig. 7d against the strands: SSIM 0.630 from that id, 0.640 from
// this one). The full
// curl's slice: water, which reads other levels, takes the ringlet out.
// `id` (the coverage read's) where the finest level has no hair.
float sharp_id(vec2 fur_uv, float id)
{
    vec4 h0 = textureLod(u_fur, vec3(fur_uv, v_slices.x), 0.0);
    return h0.a > 0.05 ? h0.b / h0.a : id;
}
#endif

// The shell pass builds this shader in variants (gl/shell_pass.c): each
// PELT_* feature below is compiled in only when the frame needs it, so the
// dry, unshadowed common case pays for none of it. The generic program
// defines them all.
void main()
{
    // Sharp across the view where the fur is seen at a grazing angle, and
    // half a level finer where the footprint is round (docs/shading.md, The fur
    // texture's filtering).
    vec2 fur_dx = dFdx(v_fur_uv), fur_dy = dFdy(v_fur_uv);
    float texels = float(textureSize(u_fur, 0).x);
#ifdef PELT_FUR_TAPS
    // Several fetches along a long footprint: sharp across the view at
    // any grazing angle (docs/shading.md, Fetches along the footprint).
    fur_taps = fur_texture_taps(fur_dx, fur_dy, texels, v_aniso, u_fur_taps, fur_lod);
    fur_step = (dot(fur_dx, fur_dx) > dot(fur_dy, fur_dy) ? fur_dx : fur_dy) / fur_taps;
#else
    fur_lod = shell_fur_texture_lod(fur_dx, fur_dy, texels, v_aniso);
#endif
    // Seen close, where a texel spans pixels, a hair keeps its own width
    // and a pixel-wide edge (docs/shading.md, The hair's edge seen close).
    fur_gain = fur_edge_gain(fur_dx, fur_dy, texels);
    // A shell the view's budget leaves out here (face-on): no fetch.
    // ... nor a sub shell it does not need (clipped but in WebGL2).
    if (v_alpha < 1.0 / 255.0 || v_sub_e < 1.0 / 255.0) discard;
    vec2 d = vec2(0.0);
    float rho = 0.0;
#ifdef PELT_WET
    vec4 t = clump_texel(u_mask, v_uv);
    rho = t.a;
#endif
#ifdef PELT_TUFTS
    // Clumps (Silva Eq. 5, Alg. 2 as docs/wetness.md reads them): sample the hair
    // rooted at q; colour and fur coordinates move together.
    vec2 q;
    vec2 lean = clump_lean(t, u_clump_lean);
    int clump = clump_lookup_texel(u_mask, t, v_uv, v_clump_profile, u_clump_tightness, lean, q);
    // The clump squeezes its strands towards the centre by k (squeeze): the
    // texture is read 1/k times as far a pixel.
    float squeeze = 1.0 - min(u_clump_tightness * rho * v_clump_profile, CLUMP_MAX_PULL);
    if (clump == CLUMP_DISPLACED) {
        d = q - v_uv;
        fur_lod -= log2(squeeze);
        fur_step /= squeeze; // the footprint as much longer
        fur_gain = max(fur_gain * squeeze, 1.0); // and its texels span less
    }
#endif
    vec2 fur_uv = v_fur_uv + d * u_fur_per_uv;
    vec4 hair = wet_hair(fur_uv, rho);
    // One more read at most: seen from the side, this shell holds the hair
    // down to the next one, the union with the hair half a gap back
    // (pelt__lod_shell_gap); in a tuft, whose hairs the clump moves, the
    // hair growing here instead, which stands if it is a stray
    // (clump_stray_hair). The two never meet, so one fetch serves both.
    vec2 second_uv = v_fur_uv;
    float gap_weight = 0.0;
#if !defined(PELT_LIGHT_PASS) && !defined(PELT_NO_GAP)
    second_uv = fur_uv - 0.5 * v_gap.xy;
    gap_weight = v_gap.z;
#endif
#ifdef PELT_TUFTS
    bool moved = clump != CLUMP_KEEP;
    if (moved) {
        second_uv = v_fur_uv;
        gap_weight = 0.0;
    }
#else
    const bool moved = false;
#endif
    if (gap_weight > 0.0 || moved) {
        vec4 second = wet_hair(second_uv, rho);
        if (!moved) hair += second * (gap_weight * (1.0 - hair.a));
#ifdef PELT_TUFTS
        if (moved && clump_stray_hair(clump, hair, second, u_wet_strays)) {
            d = vec2(0.0);
            fur_uv = v_fur_uv;
            clump = CLUMP_KEEP;
        }
#endif
    }
#ifdef PELT_TUFTS
    if (moved && !(hair.a > 0.0)) discard;
#endif
    hair = shell_view_texel(v_view, fur_edge(hair, fur_gain)) * v_alpha;
    hair.rgb /= max(hair.a, 1e-3);  // the volume is premultiplied
    if (!groom_keeps(hair.b, v_density)) discard;
    // The tuft's squeeze, the shells a ray crosses inside the hair and the
    // layer's sub shells each raise the coverage's complement to a power
    // (coverage_share, shell_lod.glsl): their exponents multiply, so one
    // log2 and one exp2 stand for clump_coverage, shell_overcount_alpha and
    // layer_share.
    float clear_log = coverage_log(hair.a);
    float tuft_e = 1.0;
#ifdef PELT_TUFTS
    // The bundle is 1/k times as dense where the read averages its
    // hairs (see docs/wetness.md): clump_coverage's exponent.
    if (clump == CLUMP_DISPLACED) tuft_e = 1.0 / clump_bundle_squeeze(squeeze, fur_lod);
#endif
#ifdef PELT_LIGHT_PASS
    // Deep opacity maps: this hair's -ln(1 - alpha) into the slices at and
    // behind its depth in the slab in front of the skin. Hair behind the
    // skin is in the body's shadow and shades nothing that is lit.
    hair.a = coverage_share(clear_log, tuft_e);
    if (hair.a < 0.05) discard;
    if (!shadow_slices_add(ivec2(gl_FragCoord.xy), v_light_depth, hair.a, o_slices0, o_slices1)) discard;
    return;
#else
    if (clear_log * tuft_e > COVERAGE_CLEAR_LOG) { // the tuft's coverage below 0.05
#ifdef PELT_INTER_SHADOW
        // Kenwright: no hair here, but the hair a step towards the light
        // casts its shadow on what lies below, with that hair's coverage.
        if (u_inter_shadow <= 0.0 || u_no_inter_shadow != 0) discard;
        float caster = fur_edge(texture(u_fur, vec3(fur_uv + v_shadow_step, v_slices.x)), fur_gain).a * v_alpha;
        if (caster < 0.05) discard;
        caster = shell_overcount_alpha(caster, v_overcount); // the caster is a hair as below
        o_color = vec4(0.0, 0.0, 0.0, layer_share(caster * u_inter_shadow * v_shadow_fade));
        return;
#else
        discard;
#endif
    }
    // The strand's shade is an sRGB value like the colours: decoded.
    vec3 base = mix(v_root, v_tip, hair.g) * shade_decode(hair.r);
#ifdef PELT_COLOR_TEXTURE
    base *= texture(u_color_tex, (v_uv + d) * u_color_scale).rgb;
#endif
    base = wet_color(base, rho, u_wet_darken); // darker, more saturated
    float spec = v_spec;
#if defined(PELT_TUFTS) && defined(PELT_RINGLETS)
    // A tuft's hair along its tuft, the others along their ringlet: one
    // light for either (a fragment's block works out both ways where its
    // pixels split, so the light's own work is done once). The free
    // hair's light from the dots the ringlets' frame carries.
    vec2 own = clump == CLUMP_DISPLACED ? shell_tuft_dots(t.xy + lean - q, rho)
                                        : ringlet_own(sharp_id(fur_uv, hair.b), rho, v_h, v_ring_l, v_ring_e, v_ring_g);
    own_light_dots(own, v_light, free_light_inverse_dots(v_ring_l.x, v_ring_e.x, rho, v_light), rho, base, spec);
#elif defined(PELT_TUFTS)
    if (clump == CLUMP_DISPLACED) tuft_light(t.xy + lean - q, rho, base, spec);
#elif defined(PELT_RINGLETS)
    shell_ringlet_light(sharp_id(fur_uv, hair.b), rho, base, spec);
#endif
    float alpha = coverage_share(clear_log, tuft_e / max(v_overcount, 1e-3) * layer_share_exponent());
    o_color = vec4(display_color(base + spec * (u_specular * u_light_color), u_exposure, u_tone), alpha);
#endif
}
