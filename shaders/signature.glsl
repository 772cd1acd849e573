// signature.glsl: where float's rounding can flip a decision
// (--precision auto).
//
// Float's rounding changes an image where it flips a discrete decision:
// which object a ray hits (and which face), whether a light is shadowed,
// which checker cell a point lies in, whether a ray enters or leaves,
// whether it is totally reflected. The float pass keeps a word per pixel
// (render_bands.c reads it, retrace.c marks from it): a 25-bit hash of its
// decisions, three bits and its camera rays' shadows. UNSURE: a decision
// with a local margin (a checker cell face, the sign of n.d, total
// internal reflection) was within its doubt of flipping, a texture's
// or gradient's color may slide by a level with the hit point
// (trace.comp, pigment_slope), an area light's penumbra may
// (penumbra_seen), or a ray passed a flat solid's or a triangle's edge
// within its doubt, or two flat faces that cross tie (edges_seen, at the
// end; trace.comp, coincident_faces).
// SENSITIVE: a boundary seen there may move by frame.limits.y pixels or
// more. A pixel is traced again in double where it is UNSURE, or where
// its hash differs from a neighbour's and one of the two is SENSITIVE:
// which object a ray hits, and shadows, have no local margin (a ray that
// misses an object cannot tell by how much; a shadow ray passing a
// sphere can: shadow_grazes, at the end), so their boundaries are
// found between neighbours; where a boundary cannot move by a tenth of a
// pixel, a flip would need it to pass that near a pixel's center (for
// shadow edges the camera sees, a fiftieth of that: SHADOWS, at the end).
// STOPPED: an UNSURE pixel is traced again, every sample, whatever else
// its rays do, so its float walk stops at that decision; its hash then
// covers the rays before it only, and the host takes it to differ from
// every neighbour's.
//
// The doubt is a bound on float's error, carried along each ray and
// measured in pixels against the footprint of its pixel (below). It is a
// first-order estimate with a safety factor, not a proof: docs/accuracy.md
// has what it was checked against.

const uint UNSURE = TP2_SIG_UNSURE;       // a decision within float's error of flipping
const uint SENSITIVE = TP2_SIG_SENSITIVE; // boundaries here move by frame.limits.y pixels or more
const uint STOPPED = TP2_SIG_STOPPED;     // the walk stopped at its first UNSURE decision
const uint SHADOWS = TP2_SIG_SHADOWS;     // the camera rays' shadows (shadow_seen)
const uint HASH = TP2_SIG_HASH;
const uint SIGNATURE_START = 2166136261u & HASH; // FNV-1a's offset basis

// Float's unit roundoff, 2^-24, times a safety factor for the operations
// one step of a ray takes (an intersection, a normal, a reflection).
const float ROUNDING = 4.0 * 5.9604645e-8;

// No edge passed (Hit.edge), and no edge test (edge_doubt).
const float NO_EDGE = 3.0e38;

// Mixes one decision into the hash (FNV-1a on a whole word, 25 bits);
// compiled out when the pass records no signatures.
void decided(inout uint sig, uint choice)
{
    if (SIGNATURES)
        sig = (((sig & HASH) ^ choice) * 16777619u & HASH) | (sig & ~HASH);
}

// A ray's doubt (Ray.doubt) is measured against the footprint of its
// pixel, which curved mirrors and lenses spread or focus just as they
// spread or focus errors (to first order, the same map carries both): x
// is how far, in pixels, what the ray meets may be off from what was
// carried to its origin; y how far its direction may be off from the
// rounding at its origin (radians, not yet in pixels); z and w the
// footprint: its width across the ray at the origin and how fast that
// grows with distance (radians; negative while it converges). y's sign
// says whether the doubt is still the ray's own rounding (own_rounding):
// positive for camera rays and rays mirrored by surfaces flat across
// their footprint, negative once a curved mirror or a lens has spread or
// focused the beam, whose first-order map then carries a bound far above
// the error.

// What is known at a hit at distance t: how far, in pixels, the hit point
// may be off; how far along the surface (spread by a grazing ray: cosine
// = |n.d|); how far the angle of incidence may be off; the footprint's
// width across the ray and along the surface; and the rounding of the
// normal computed there (scale: the size of the numbers that computed the
// hit; bend: the largest magnitude of the surface's curvature). own: how
// far, in pixels, by what is known to be close to float's error (seen):
// all of it while the doubt is the ray's own rounding, else the hit's
// fresh rounding alone, over a footprint no narrower than a camera
// pixel's at that distance (a lens's focus narrows the model's footprint
// far more than it shrinks errors).
struct HitDoubt {
    float pixels, along, angle, width, width_along, turn, own;
};

// Whether a doubt is still the ray's own rounding (y's sign bit, so that
// a half's zero keeps it).
bool own_rounding(vec4 doubt)
{
    return (floatBitsToUint(doubt.y) & 0x80000000u) == 0u;
}

HitDoubt doubt_at(vec4 doubt, float t, float scale, float cosine, float bend)
{
    HitDoubt h;
    float grazing = 1.0 / max(cosine, 1e-6);
    h.width = abs(doubt.z + doubt.w * t);
    h.width_along = h.width * grazing;
    h.pixels = doubt.x + (abs(doubt.y) * t + ROUNDING * (scale + t)) / h.width;
    h.along = h.pixels * h.width_along;
    h.turn = ROUNDING * (1.0 + abs(bend) * scale);
    h.angle = h.pixels * (abs(doubt.w) + abs(bend) * h.width_along) + abs(doubt.y) + h.turn;
    h.own = own_rounding(doubt) ? h.pixels
                                : ROUNDING * (scale + t) / max(h.width, frame.limits.z * t);
    return h;
}

// How far the distance of a hit at t may be off: its intersection's
// fresh rounding, and the ray's own doubt times the grazing spread.
float distance_doubt(HitDoubt h, float t, float scale)
{
    return 2.0 * ROUNDING * (scale + t) + h.pixels * h.width_along;
}

// Whether the nearest crossing may not be the nearest: the next one
// tested lies `margin` further along the ray,
// within what the two distances may be off: each has the fresh rounding
// of its intersection, and the ray's own doubt moves them apart by up to
// its width times the grazing spread. Two surfaces that cross, or nearly
// touch, make this margin tiny along the curve where they meet. Margin 0
// on faces that coincide in double too is sure (shapes.glsl,
// coincident_faces: the caller tests it).
bool nearer_unsure(float margin, HitDoubt h, float t, float scale)
{
    return margin < distance_doubt(h, t, scale);
}

// How far, in pixels, boundaries beyond the ray's origin may move.
float far_pixels(vec4 doubt)
{
    return doubt.x + (abs(doubt.y) + ROUNDING) / abs(doubt.w);
}

// The same for boundaries beyond: HitDoubt.own's share of far_pixels.
float own_far_pixels(vec4 doubt)
{
    return own_rounding(doubt) ? far_pixels(doubt) : ROUNDING / max(abs(doubt.w), frame.limits.z);
}

// A mirrored ray's direction doubt y (positive), signed as own_rounding
// says.
float owned(float y, vec4 doubt, HitDoubt h, vec2 curving)
{
    bool gentle = 2.0 * max(abs(curving.x), abs(curving.y)) * h.width_along <= abs(doubt.w);
    return own_rounding(doubt) && gentle ? y : -y;
}

// The doubt of a ray leaving the hit, mirrored or refracted (eta the ratio
// of indices, cos_t the cosine it leaves at). curving holds the least and
// the greatest curvature of the surface as the ray meets it (positive
// where it bulges toward the ray); of these, the one that spreads the
// beam least is taken, so that the footprint is never overestimated. A
// mirror adds twice the normal's turn over the footprint to the beam's
// spread, a refraction bends it by the paraxial law
// (n'u' = nu - h (n' - n) / R).
// A mirrored ray's doubt stays its own rounding (y > 0) where the mirror
// turns the beam by no more than its own spread across the footprint (a
// floor that is a sphere of radius 1000, not a ball); a refracted ray's
// never does (flat glass kept it too, and marked 1.4 times box.txt's
// pixels at 1920 x 1080, none of which then came out different).
vec4 mirrored_doubt(vec4 doubt, HitDoubt h, vec2 curving)
{
    return vec4(h.pixels, owned(2.0 * h.turn, doubt, h, curving), h.width,
                doubt.w + 2.0 * curving.x * h.width_along);
}

vec4 refracted_doubt(vec4 doubt, HitDoubt h, vec2 curving, float eta, float cos_t)
{
    float c = eta > 1.0 ? curving.x : curving.y;
    return vec4(h.pixels, -(1.0 + eta) * h.turn / max(cos_t, 1e-3), h.width,
                eta * doubt.w + (eta - 1.0) * c * h.width_along);
}

// A doubt parked on the walk's stack, in half precision: half the memory
// traffic of lavapipe's stack (10-bit mantissas lose nothing that the
// safety factor in ROUNDING does not cover; past 65504 a half is infinite,
// which only says more).
uvec2 packed_doubt(vec4 d)
{
    return uvec2(packHalf2x16(d.xy), packHalf2x16(d.zw));
}

vec4 unpacked_doubt(uvec2 h)
{
    return vec4(unpackHalf2x16(h.x), unpackHalf2x16(h.y));
}

// Whether the float pass is done with a pixel of signature sig: it is
// traced again in double (compiled out when there are no signatures).
bool unsure(uint sig)
{
    return SIGNATURES && (sig & UNSURE) != 0u;
}

// Whether a decision that a flip of changes the pixel by up to `stake`
// counts (frame.limits.w: what is less cannot move a pixel by a level).
bool at_stake(float stake)
{
    return SIGNATURES && stake >= frame.limits.w;
}

// Marks sig SENSITIVE where boundaries seen here may move by `pixels`.
// With SAMPLES rays per pixel (stratified, or spread by a lens) a boundary
// passes near SAMPLES times as many rays, so it counts from a SAMPLES-th
// of frame.limits.y (a flip of one of them weighs a SAMPLES-th, which
// `stake` says). What is known to be close to float's error (`own`: a
// ray's own rounding, a hit's fresh rounding; HitDoubt.own) counts from
// OWN_SHARE of that. Far from 0, or on a sphere of radius 1e7, that
// error is a share of every footprint and moves long edges by a few
// hundredths of a pixel, flipping that share of the pixels along them
// (random scenes with 17 and 14 pixels off by more than 8 levels at 400
// x 300: docs/accuracy.md). The rest of a doubt carried through
// curved mirrors and lenses holds the beam's spread, far above the
// error, and counts from the tenth.
const float OWN_SHARE = 1.0 / 10.0;

void seen(inout uint sig, float pixels, float own, float stake)
{
    if (at_stake(stake) && max(pixels, own / OWN_SHARE) * float(SAMPLES) >= frame.limits.y)
        sig |= SENSITIVE;
}

// Marks sig UNSURE where the hit point itself may be off by frame.limits.y
// pixels or more: a steep highlight or texture moved that far changes the
// pixel by levels with no decision flipped (a far camera under a narrow
// field of view, where float's error is a share of every footprint). For
// camera rays only, whose doubt is their own rounding: deeper, it carries
// the beam's spread through lenses, and in glass interiors would mark
// pixels that no measured image got wrong (docs/accuracy.md).
void shifted(inout uint sig, float pixels, float stake)
{
    if (at_stake(stake) && pixels >= frame.limits.y)
        sig |= UNSURE;
}

// The camera rays' shadows (SHADOWS): which point lights a pixel's camera
// rays saw shadowed, a bit per class of lights (j % 4), over its samples.
// The host marks both pixels wherever these differ between neighbours,
// SENSITIVE or not. A shadow edge on a surface the camera sees, moved by
// rounding by less than the tenth of a pixel that makes a pixel
// SENSITIVE, still flips the pixels whose centers lie that near it, and
// a long edge passes that near some: a course file's floor, a sphere of
// radius 100, moves its edges by 0.0016-0.006 pixel, and 75 pixels
// flipped at 1920 x 1080. They are recorded where rounding may move them
// by SHADOW_SHARE of that tenth or more: an edge moved by less needs 500
// pixels of length for each pixel it may flip. (Recorded at any move,
// they marked quadric.txt's 5.4% of pixels instead of 2.4%; recorded at
// any depth, spheres.txt's 9.9% instead of 5.4%, as deeper rays' doubts
// grow through curved mirrors. docs/accuracy.md.) Lit and unlit (the
// light behind the surface, or no hit) are not told apart, so that
// terminators and silhouettes are not marked for it. One flip changes a
// bit wherever no other light of its class shadows the point (always,
// with up to four lights).
const float SHADOW_SHARE = 1.0 / 50.0;

// Records that point light j shadows a camera ray's hit, in the loop over
// lights; after it, shadows_kept says whether that hit keeps them.
void shadow_seen(inout uint sig, int depth, int j, bool shadowed)
{
    if (SIGNATURES && depth == 0 && shadowed)
        sig |= TP2_SIG_SHADOW_LOW << (j & 3);
}

// Clears SHADOWS after a camera ray's lights unless the hit's shadow
// edges may move by `pixels`, SHADOW_SHARE of what counts or more; so the
// last camera sample of a pixel decides (the samples of a pixel meet
// much the same doubt). Whatever each light adds: a light too dim to
// move the pixel by a level whose edge moves by 0.002 pixel is rare.
// (Deciding before the loop whether to record, with a flag the loop
// reads, made spheres.txt's float pass 5% slower; this way 0.5%.)
void shadows_kept(inout uint sig, int depth, float pixels, float stake)
{
    if (SIGNATURES && depth == 0 &&
        !(at_stake(stake) && pixels * float(SAMPLES) >= SHADOW_SHARE * frame.limits.y))
        sig &= ~SHADOWS;
}

// How far a shadow ray's origin, a hit point, may be off along its
// surface (twice, a safety factor): its fresh rounding, `sizes` (a floor
// that is a sphere of radius 100 moves its points by 5e-5, and the shadow
// edges seen in a mirror flip), and a camera ray's doubt along the
// surface; a deeper ray's only where that doubt is known to be close to
// float's error (HitDoubt.own): through flat mirrors and gentle ones, a
// sphere floor of radius 1000 moves the point a mirrored ray meets by
// 1e-4, and shadows thinner than that flipped
// (tests/stress/needle-shadows-mirrored). Deeper rays' whole doubts grow
// with the beam through mirror and glass balls, and counted here they
// marked spheres.txt's 9.0% of pixels instead of 5.4% (docs/accuracy.md).
float shadow_origin_doubt(int depth, HitDoubt h, float sizes)
{
    float along = depth == 0 ? h.along : h.own * h.width_along;
    return 2.0 * (along + ROUNDING * sizes);
}

// Marks sig UNSURE where a shadow ray passed a sphere (hit or missed it)
// nearer than the point it left may be off (shadow_origin_doubt): `graze`
// is how near, less the sphere test's own rounding (shapes.glsl,
// hit_sphere). (A miss cannot tell by how much for most kinds; for a
// sphere it is the closest approach its test computes anyway; a flat
// solid's edges are edge_graze's, shapes.glsl.)
void shadow_grazes(inout uint sig, float graze, int depth, HitDoubt h, float sizes, float stake)
{
    if (at_stake(stake) && graze < shadow_origin_doubt(depth, h, sizes))
        sig |= UNSURE;
}

// The doubt a ray's trace_scene takes edges with (intersect.glsl,
// shapes.glsl: edge_graze): how far its origin and its direction
// (radians) may be off, twice what doubt_at's terms hold (a safety
// factor of 2, as shadow_grazes'). Neighbours find the boundaries of
// which object a ray meets only where rounding may move them by a share
// of a pixel (SENSITIVE); a straight edge along a row of pixel centers (a
// box's or a mesh's, seen from a camera on its axes: docs/accuracy.md) flips a run of pixels however little it moves. The edge
// tests (edge_graze, exit_graze, triangle_graze) count only doubts
// that reach at most TP2_EDGE_REACH of the scene's scale (camera rays,
// flat mirrors' and flat glass's): a beam spread by curved mirrors and
// lenses is SENSITIVE's.
vec2 edge_doubt(vec4 doubt, float stake)
{
    if (!at_stake(stake))
        return vec2(-NO_EDGE, 0.0);
    return 2.0 * vec2(doubt.x * abs(doubt.z), abs(doubt.y) + doubt.x * abs(doubt.w));
}

// The same for a shadow ray from a hit point: its origin's doubt
// (shadow_origin_doubt); its direction's rounding is the test's own.
vec2 shadow_edge_doubt(int depth, HitDoubt h, float sizes, float stake)
{
    if (!at_stake(stake))
        return vec2(-NO_EDGE, 0.0);
    return vec2(shadow_origin_doubt(depth, h, sizes), 0.0);
}

// Marks sig UNSURE where a ray passed an edge within its doubt, nearer
// than what it hit (Hit.edge and Hit.t) or at most `behind` beyond it: a
// corner lying on the surface hit (a triangle's, resting on a floor, on a
// pixel center's ray) is as far as the hit, and float may put it a hair
// behind (tests/stress/triangle-corners-on-floor.txt).
void edges_seen(inout uint sig, float edge, float t, float behind)
{
    if (edge < NO_EDGE && edge <= t + behind)
        sig |= UNSURE;
}

// What area sample `lit` adds, as the lit or the shadowed half of a
// penumbra (penumbra_seen takes the most of each over the samples).
vec2 area_share(vec3 lit, bool shadowed)
{
    float most = max(lit.r, max(lit.g, lit.b));
    return shadowed ? vec2(0.0, most) : vec2(most, 0.0);
}

// The arealight's samples are turned per pixel (shade.glsl, area_sample),
// so their shadow edges cannot be found between neighbours as the point
// lights' are. A penumbra, where some of a hit's samples are shadowed and
// some not, is where those edges lie, one per sample, and rounding moves
// each as it moves a point light's: a camera ray's hit there is UNSURE
// where that may be SHADOW_SHARE of what counts (as SHADOWS), a deeper
// ray's where its known rounding (HitDoubt.own) may be OWN_SHARE of it
// (as seen). A flip weighs the most one sample adds. Far from 0, where
// float's rounding moves edges by hundredths of a pixel, penumbras were
// left 2-5 levels off at a scattered few pixels in a hundred (random
// scene 556 of docs/accuracy.md).
void penumbra_seen(inout uint sig, int depth, vec2 penumbra, HitDoubt h, float stake)
{
    float moved = depth == 0 ? h.pixels / SHADOW_SHARE : h.own / OWN_SHARE;
    if (at_stake(stake * max(penumbra.x, penumbra.y)) && min(penumbra.x, penumbra.y) > 0.0 &&
        moved * float(SAMPLES) >= frame.limits.y)
        sig |= UNSURE;
}
