// The outline's hairs (docs/reference.md, The outline's hairs, drawn as
// geometry): each fin near the silhouette also carries some of the hairs
// it stands for as geometry, so the outline shows single hairs against the
// background, as the strand reference does, where the fin texture read at
// a pixel's footprint can only show their average. A hair's draws come
// from a hash of its fin's two vertices and its number on the fin, so it
// stays the same hair from frame to frame. Every function here is
// mirrored by its pelt__outline_* in core/fur/fins.c (test_parity).

// The most hairs a fin carries: the hairs beyond its share are collapsed.
const int OUTLINE_HAIRS_MAX = 32; // PELT__OUTLINE_HAIRS_MAX

// Murmur3's 32-bit finaliser (pelt__hash32).
uint outline_hash(uint h)
{
    h ^= h >> 16u;
    h *= 0x85ebca6bu;
    h ^= h >> 13u;
    h *= 0xc2b2ae35u;
    h ^= h >> 16u;
    return h;
}

// The seed of hair k on the fin between fin vertices a and b.
uint outline_seed(uint a, uint b, uint k)
{
    return outline_hash(a * 0x27d4eb2du ^ outline_hash(b ^ (k * 0x165667b1u)));
}

// The hair's i-th draw, uniform in [0, 1): 24 bits of the hash.
float outline_random(uint seed, uint i)
{
    return float(outline_hash(seed + i * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0);
}

// How much of hair k a fin shows: its share of the hairs (count, the fin's
// edge times the hairs a tile of edge holds, may be fractional) and its
// fin's fade against the hair's own threshold `show` (so a fainter fin has
// fewer hairs, each as sharp, rather than fainter ones), a fade of 0.25
// wide so that none pops. Where the fin stands for more hairs than it
// draws, each drawn one covers for count / OUTLINE_HAIRS_MAX of them.
float outline_alpha(float k, float count, float fade, float show)
{
    return clamp(count - k, 0.0, 1.0) * clamp((fade - show) * 4.0, 0.0, 1.0) *
           max(1.0, count / float(OUTLINE_HAIRS_MAX));
}

// The outline's hairs take over from the fin texture's quads where its
// hair is sub-pixel but countable: between OUTLINE_LOW_PX and
// OUTLINE_FULL_PX of the hair's length on screen they fade in (shorter,
// every hair is a fraction of a pixel and the texture's average covers as
// the hairs do), up to OUTLINE_FULL_PX they stand alone, and by
// OUTLINE_NONE_PX they are gone: there the texture resolves its hairs and
// the shells' layers draw them across the outline themselves.
const float OUTLINE_LOW_PX = 4.0;   // PELT__OUTLINE_LOW_PX
const float OUTLINE_FULL_PX = 16.0; // PELT__OUTLINE_FULL_PX
const float OUTLINE_NONE_PX = 32.0; // PELT__OUTLINE_NONE_PX

float outline_reach(float hair_px)
{
    float in_ = clamp((hair_px - OUTLINE_LOW_PX) / OUTLINE_LOW_PX, 0.0, 1.0);
    float out_ = clamp((OUTLINE_NONE_PX - hair_px) / (OUTLINE_NONE_PX - OUTLINE_FULL_PX), 0.0, 1.0);
    return in_ * out_;
}

// The share of a fin's outline its hairs carry: outline_reach of its
// hair's length on screen, none where the fur holds water (the fin
// texture's quads gather it into the shells' tufts).
float outline_share(float hair_px, float wetness)
{
    return outline_reach(hair_px) * (1.0 - clamp(wetness, 0.0, 1.0));
}

// The hair's lean along the edge at its tip in its root widths, from its
// draw r: up to one either way, as the fur texture's strands lean (two
// radii over the full height, core/fur/furtex.c).
float outline_lean(float r)
{
    return (r - 0.5) * 2.0;
}

// The hair's point at height h: the fin's strand point p at the hair's
// place on the edge, its offset from the root scaled by the hair's length
// (0.6 to 1 of the full length from the draw r_len, as the fur texture's
// strands), leaning along `along` (the edge's unit direction times the
// hair's root width) by outline_lean times h. w: the length share.
vec4 outline_shape(vec3 root, vec3 p, vec3 along, float r_len, float r_lean, float h)
{
    float share = 0.6 + 0.4 * r_len;
    return vec4(root + share * (p - root) + along * (outline_lean(r_lean) * h), share);
}
