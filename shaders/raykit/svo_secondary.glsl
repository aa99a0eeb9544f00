// raykit — svo_secondary.glsl: secondary rays through sparse voxel octrees: shadow rays,
// reflection and refraction with Fresnel and explicit total internal reflection, and
// heterogeneous media (a refractive index and a Beer–Lambert absorption per voxel, the ray stepped
// voxel by voxel and refracted wherever the index changes).
//
// Shared GLSL/C++ source (include/raykit/svo_secondary.hpp is the C++ build). Built on
// svo_traverse.glsl and fresnel.glsl. It fixes what Wilks ("Real-time GPU Ray Tracing with
// Volumetric Effects") left open:
//   - Offsets: secondary rays start 1/64 voxel off the face they leave (snapped onto its lattice
//     plane first), not 5.7 voxels.
//   - TIR: total internal reflection reflects, instead of refracting along a zero vector.
//   - Fresnel: the reflectance is the exact dielectric Fresnel (or its fast form), at cos_i of
//     the interface.
//   - Stepping: a medium is crossed exactly voxel by voxel (a 3D DDA over the leaf grid), not by a
//     fixed fraction of the scene, so no feature thinner than a step is skipped.
//   - Absorption: integrated per voxel segment.
// Interface normals are the voxel faces the ray crosses (a voxel model has no other surface);
// a GLSL shader can substitute stored smooth normals (RK_SVO_INTERFACE_NORMAL below).
//
// Media: a voxel's medium is vec4(index, absorption rgb per object-space unit) from its material
// (SvoMaterial.ior, .absorption; raykit::svo_media_table() packs them). Shaders read it through
// RK_SVO_MEDIUM(media, attr). Unless the including shader defines that macro (do so on GLSL ES 3.1
// drivers without fragment-stage SSBOs, e.g. reading textures), this file declares two SSBOs
// (GLSL only):
//   RkSvoMaterialIds { uint rk_svo_material_ids[]; } at RK_SVO_MATERIAL_IDS_BINDING (default 6),
//   RkSvoMedia { vec4 rk_svo_media[]; } at RK_SVO_MEDIA_BINDING (default 7).
// In C++ the media argument is an rk_svo_media_ref of two pointers.
//
// Features:
//   RK_SVO_SECONDARY_FRESNEL_FAST (default 0): 1 uses rk_fresnel_dielectric_fast (no sqrt, 1.7e-3 max error
//       for glass) for external reflection; internal reflection stays exact.
//   RK_SVO_SECONDARY_ABSORPTION (default 1): 0 drops the Beer–Lambert transmittance (no exp per voxel).
//   RK_SVO_SECONDARY_MAX_STEPS (default 4096, a plain integer): bound on the voxels one rk_svo_march crosses.
//
// @rk-variants RK_SVO_SECONDARY_FRESNEL_FAST=1 | RK_SVO_SECONDARY_ABSORPTION=0 | RK_SVO_SECONDARY_FRESNEL_FAST=1 RK_SVO_SECONDARY_MAX_STEPS=64 | RK_SVO_BUFFER_TEXTURE=1 RK_SVO_MEDIUM(m,a)=vec4(1.5,0.0,0.0,0.0) RK_SVO_INTERFACE_NORMAL(m,a,n)=normalize((n)+vec3(0.0,1e-3,0.0))
// @rk-es 310
#ifndef RK_SVO_SECONDARY_GLSL
#define RK_SVO_SECONDARY_GLSL

#include "common.glsl"
#include "fresnel.glsl"
#include "svo_traverse.glsl"

#ifndef RK_SVO_SECONDARY_FRESNEL_FAST
#define RK_SVO_SECONDARY_FRESNEL_FAST 0
#endif
#if RK_SVO_SECONDARY_FRESNEL_FAST < 0 || RK_SVO_SECONDARY_FRESNEL_FAST > 1
#error "RK_SVO_SECONDARY_FRESNEL_FAST must be 0 (exact Fresnel) or 1 (fast Fresnel)"
#endif
RK_OPTION_CHECK(rk_option_svo_secondary_fresnel_fast, RK_SVO_SECONDARY_FRESNEL_FAST);
#ifndef RK_SVO_SECONDARY_ABSORPTION
#define RK_SVO_SECONDARY_ABSORPTION 1
#endif
#if RK_SVO_SECONDARY_ABSORPTION < 0 || RK_SVO_SECONDARY_ABSORPTION > 1
#error "RK_SVO_SECONDARY_ABSORPTION must be 0 (no absorption) or 1 (Beer-Lambert absorption)"
#endif
RK_OPTION_CHECK(rk_option_svo_secondary_absorption, RK_SVO_SECONDARY_ABSORPTION);
#ifndef RK_SVO_SECONDARY_MAX_STEPS
#define RK_SVO_SECONDARY_MAX_STEPS 4096
#endif
#if RK_SVO_SECONDARY_MAX_STEPS < 1 || RK_SVO_SECONDARY_MAX_STEPS > 16777216
#error "RK_SVO_SECONDARY_MAX_STEPS must be in 1..2^24"
#endif
RK_OPTION_CHECK(rk_option_svo_secondary_max_steps, RK_SVO_SECONDARY_MAX_STEPS);
#ifndef RK_SVO_MATERIAL_IDS_BINDING
#define RK_SVO_MATERIAL_IDS_BINDING 6
#endif
#if RK_SVO_MATERIAL_IDS_BINDING < 0 || RK_SVO_MATERIAL_IDS_BINDING > 95
#error "RK_SVO_MATERIAL_IDS_BINDING must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_svo_material_ids_binding, RK_SVO_MATERIAL_IDS_BINDING);
#ifndef RK_SVO_MEDIA_BINDING
#define RK_SVO_MEDIA_BINDING 7
#endif
#if RK_SVO_MEDIA_BINDING < 0 || RK_SVO_MEDIA_BINDING > 95
#error "RK_SVO_MEDIA_BINDING must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_svo_media_binding, RK_SVO_MEDIA_BINDING);

#ifdef __cplusplus
/// C++: where a voxel's medium comes from (material id stream and media table). (The C++ build
/// ignores an RK_SVO_MEDIUM definition: a macro must not change C++ behaviour per translation unit.)
struct rk_svo_media_ref {
    const uint* material_ids;
    const vec4* media;
};
#define RK_SVO_MEDIA rk_svo_media_ref
#define RK_SVO_MEDIUM_(m, attr) ((m).media[(m).material_ids[(attr)]])
#else
#define RK_SVO_MEDIA uint
#ifdef RK_SVO_MEDIUM
#define RK_SVO_MEDIUM_(m, attr) RK_SVO_MEDIUM(m, attr)
#else
layout(std430, binding = RK_SVO_MATERIAL_IDS_BINDING) readonly buffer RkSvoMaterialIds { uint rk_svo_material_ids[]; };
layout(std430, binding = RK_SVO_MEDIA_BINDING) readonly buffer RkSvoMedia { vec4 rk_svo_media[]; };
#define RK_SVO_MEDIUM_(m, attr) rk_svo_media[rk_svo_material_ids[(attr)]]
#endif
#endif

// The normal of an interface (GLSL only): by default the voxel face the ray crosses. A shader
// may define RK_SVO_INTERFACE_NORMAL(media, attr, face_n) before including this file to use, say,
// the stored smooth normal of the voxel `attr` that carries the surface (samples/common/rk_svo_gl.hpp
// does); the C++ build always uses the face (a macro must not change C++ behaviour per translation
// unit).
#if defined(__cplusplus) || !defined(RK_SVO_INTERFACE_NORMAL)
#define RK_SVO_INTERFACE_NORMAL_(media, attr, face_n) (face_n)
#define RK_SVO_SECONDARY_HOOKED_NORMAL_ 0
#else
#define RK_SVO_INTERFACE_NORMAL_(media, attr, face_n) RK_SVO_INTERFACE_NORMAL(media, attr, face_n)
#define RK_SVO_SECONDARY_HOOKED_NORMAL_ 1
#endif

/// rk_svo_safe_normalize: v / |v| without overflow or underflow (scaled by its largest component
/// first); `fallback` when v is zero, denormal-small or not finite. Cost: 1 max, 2 div, 1 sqrt.
RK_INLINE vec3 rk_svo_safe_normalize(vec3 v, vec3 fallback)
{
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (!(m >= RK_FLT_MIN && m <= RK_FLT_MAX)) return fallback;
    vec3 w = v / m;
    return w / length(w);
}

/// rk_svo_voxel_size: edge of a node of `level` in object units. Exact (power-of-two scaling).
RK_INLINE float rk_svo_voxel_size(rk_svo_tree tree, uint level)
{
    return tree.root_size * uintBitsToFloat(uint(127 - int(min(level, 126u))) << 23u);
}

/// rk_svo_secondary_origin: where a secondary ray in direction `dir` starts from a point `p` on a
/// node face of `level` with unit axis normal `face_n` (rk_svo_trace_hit.normal): p with its
/// coordinate along the normal snapped onto the face's lattice plane and moved to the side `dir`
/// goes by 1/64 voxel, or the traversal's resolution (4 x 2^-23 root sizes) or 4 ULPs of the
/// coordinate where those are more (at most half a voxel: the start stays in the empty cell next to
/// the face), so it neither re-hits the face it leaves nor tunnels through a neighbour (Wilks's 5.7
/// voxels could). Domain: p within half a voxel of the face plane: use rk_svo_hit_point, which puts
/// a hit exactly on it whatever the ray's rounding. Cost: ~12 flops, 1 floor, 1 div.
RK_INLINE vec3 rk_svo_secondary_origin(vec3 p, vec3 face_n, vec3 dir, rk_svo_tree tree, uint level)
{
    // Snap the coordinate along the normal onto the face's lattice plane (removes the hit point's
    // rounding, however far the primary ray came from), then step 1/64 voxel off it, or 4 ULPs of
    // the coordinate where that is more.
    float voxel = rk_svo_voxel_size(tree, level);
    uint a = abs(face_n.x) > 0.5f ? 0u : (abs(face_n.y) > 0.5f ? 1u : 2u);
    float pa = a == 0u ? p.x : (a == 1u ? p.y : p.z);
    float ra = a == 0u ? tree.root_min.x : (a == 1u ? tree.root_min.y : tree.root_min.z);
    float plane = ra + floor((pa - ra) / voxel + 0.5f) * voxel;
    // At least the traversal's own resolution (4 x 2^-23 root sizes: half a voxel at depth 20, so the
    // start stays inside the empty cell the hit ray came through) and 4 ULPs of the coordinate.
    float off = max(max(voxel * 0.015625f, tree.root_size * 4.76837158e-7f), abs(plane) * 4.8e-7f);
    float q = plane + ((a == 0u ? dir.x : (a == 1u ? dir.y : dir.z)) >= 0.0f ? off : -off);
    return vec3(a == 0u ? q : p.x, a == 1u ? q : p.y, a == 2u ? q : p.z);
}

/// rk_svo_hit_point: the point where a ray (origin, dir as given to rk_svo_trace) entered the node of
/// `hit`: origin + dir * t, with the coordinate along the entry normal set exactly onto the entered
/// face's plane (a far origin's rounding can otherwise put it voxels off at depth >= 16). For an
/// origin inside the node (t = 0) the origin itself. Cost: 1 mad, ~6 flops.
RK_INLINE vec3 rk_svo_hit_point(rk_svo_tree tree, vec3 origin, vec3 dir, rk_svo_trace_hit hit)
{
    vec3 p = origin + dir * hit.t;
    if (!(hit.t > 0.0f)) return p;
    float size = rk_svo_voxel_size(tree, hit.level);
    float px = tree.root_min.x + (float(hit.cell.x) + (hit.normal.x > 0.0f ? 1.0f : 0.0f)) * size;
    float py = tree.root_min.y + (float(hit.cell.y) + (hit.normal.y > 0.0f ? 1.0f : 0.0f)) * size;
    float pz = tree.root_min.z + (float(hit.cell.z) + (hit.normal.z > 0.0f ? 1.0f : 0.0f)) * size;
    return vec3(hit.normal.x != 0.0f ? px : p.x, hit.normal.y != 0.0f ? py : p.y, hit.normal.z != 0.0f ? pz : p.z);
}

/// rk_svo_shadowed: whether anything in the octree lies between a hit (point `p` on a face with
/// normal `face_n`, at `level`) and a light `light_dist` away in unit direction `to_light`
/// (RK_FLT_MAX for a directional light); p from rk_svo_hit_point. A geometry-only rk_svo_trace: no
/// attribute is read.
RK_INLINE bool rk_svo_shadowed(RK_SVO_BUF buf, rk_svo_tree tree, vec3 p, vec3 face_n, uint level, vec3 to_light,
                               float light_dist)
{
    vec3 o = rk_svo_secondary_origin(p, face_n, to_light, tree, level);
    return rk_svo_trace(buf, tree, o, to_light, light_dist, vec2(0.0f)).hit;
}

/// What happens to a ray at an interface between indices n1 (incident side) and n2.
struct rk_svo_interface {
    vec3 reflected;     ///< mirror direction
    vec3 transmitted;   ///< refracted direction (the mirror direction under TIR)
    float reflectance;  ///< Fresnel reflectance (1 under TIR)
    bool tir;           ///< total internal reflection: no transmitted ray
};

/// rk_svo_interface_at: reflection and refraction of the unit direction `d` at a surface with unit
/// normal `n` (either orientation; it is turned to face the ray) between media n1 -> n2. The
/// reflectance is exact Fresnel, or its fast form for external reflection with
/// RK_SVO_SECONDARY_FRESNEL_FAST=1; matched indices give 0 and an unbent ray. Cost: ~1 sqrt, 2 div.
RK_INLINE rk_svo_interface rk_svo_interface_at(vec3 d, vec3 n, float n1, float n2)
{
    vec3 nf = dot(d, n) > 0.0f ? -n : n;
    float eta = n2 / max(n1, RK_FLT_MIN);
    float cos_i = rk_saturate(-dot(d, nf));
    rk_svo_interface r;
    r.reflected = d + (2.0f * cos_i) * nf;
    vec3 t;
    r.tir = !rk_refract(d, nf, eta, t);
    r.transmitted = t;
#if RK_SVO_SECONDARY_FRESNEL_FAST
    r.reflectance = r.tir ? 1.0f : (eta >= 1.0f ? rk_fresnel_dielectric_fast(cos_i, eta) : rk_fresnel_dielectric(cos_i, eta));
#else
    r.reflectance = r.tir ? 1.0f : rk_fresnel_dielectric(cos_i, eta);
#endif
    return r;
}

/// Where rk_svo_march left the medium.
struct rk_svo_march_result {
    bool left;            ///< false: RK_SVO_SECONDARY_MAX_STEPS reached inside the volume
    vec3 exit_point;      ///< on the face of the last occupied voxel
    vec3 exit_normal;     ///< that face's unit axis normal, pointing out of the volume
    vec3 dir;             ///< the direction after refracting out (unit)
    vec3 transmittance;   ///< Beer–Lambert absorption along the path times (1 - R) at every refraction
    float path;           ///< object-space length travelled inside
    uint steps;           ///< cells crossed (the look-ahead's included)
    uint interfaces;      ///< refractions, internal reflections and re-entries on the way (exits included)
};

/// rk_svo_march: follows a ray through the occupied voxels of the leaf level, from `p` (on or just
/// inside the face through which it entered the voxel at `cell`) in unit direction `d`, inside a
/// medium of index `n_in` and absorption `absorb_in`, until it leaves occupied space into a
/// medium of index `n_out`. Each voxel is a medium (RK_SVO_MEDIUM); where the index changes the ray
/// refracts at the face crossed (or reflects totally); on the way out it refracts into n_out, or
/// reflects back in under TIR and goes on. Absorption is integrated exactly per voxel segment.
/// After leaving, the walk looks three cells further (every cell the ray crosses within a voxel of
/// its exit): where it meets an occupied voxel there, the ray refracts back in and the march goes
/// on, so a staircase re-entry a fraction of a voxel after an exit is followed exactly (a
/// restarted trace's offset could step past it). The result describes the last exit.
/// Cost per voxel: one rk_svo_lookup (<= depth + 3 loads), 1 exp (with absorption), ~40 flops.
/// Precision: positions are held in voxel units of the whole grid (float spacing 2^(depth-24)
/// voxel), so media are for trees up to depth ~16 (1/256 voxel); deeper ones drift.
RK_INLINE rk_svo_march_result rk_svo_march(RK_SVO_BUF buf, rk_svo_tree tree, RK_SVO_MEDIA media, vec3 p, vec3 d, uvec3 cell,
                                           float n_in, vec3 absorb_in, float n_out)
{
    rk_svo_march_result r;
    r.left = false;
    r.exit_point = p;
    r.exit_normal = vec3(0.0f);
    r.dir = d;
    r.transmittance = vec3(1.0f);
    r.path = 0.0f;
    r.steps = 0u;
    r.interfaces = 0u;
    if (!(max(max(abs(d.x), abs(d.y)), abs(d.z)) >= RK_FLT_MIN)) return r;  // no direction: stays put
    float voxel = rk_svo_voxel_size(tree, tree.depth);
    float inv_voxel = 1.0f / voxel;
    int side = int(1u << tree.depth);
    // Voxel-unit coordinates q in [0, 2^depth]^3.
    vec3 q = (p - tree.root_min) * inv_voxel;
    ivec3 c = ivec3(cell);
    float n_cur = n_in;
    vec3 absorb = absorb_in;
    vec3 dir = d;
    uint cur_attr = 0u;  // the current voxel's attributes: only a substituted normal needs them
#if RK_SVO_SECONDARY_HOOKED_NORMAL_
    cur_attr = rk_svo_lookup(buf, tree.desc_words, tree.brick_base_word, tree.depth, cell, tree.depth).attr;
#endif
    uint ahead = 0u;  // empty cells walked since the last exit (0: inside the medium)
    for (uint it = 0u; it < uint(RK_SVO_SECONDARY_MAX_STEPS); ++it) {
        // Distance (voxel units) to the cell's exit plane on each axis.
        vec3 lo = vec3(c);
        float tx = dir.x > 0.0f ? (lo.x + 1.0f - q.x) / dir.x : (dir.x < 0.0f ? (lo.x - q.x) / dir.x : RK_FLT_MAX);
        float ty = dir.y > 0.0f ? (lo.y + 1.0f - q.y) / dir.y : (dir.y < 0.0f ? (lo.y - q.y) / dir.y : RK_FLT_MAX);
        float tz = dir.z > 0.0f ? (lo.z + 1.0f - q.z) / dir.z : (dir.z < 0.0f ? (lo.z - q.z) / dir.z : RK_FLT_MAX);
        float t = max(min(tx, min(ty, tz)), 0.0f);
        uint ax = tx <= ty && tx <= tz ? 0u : (ty <= tz ? 1u : 2u);
        // Through this voxel's medium (an empty cell of the look-ahead has none).
        if (ahead == 0u) {
            float seg = t * voxel;
            r.path += seg;
#if RK_SVO_SECONDARY_ABSORPTION
            r.transmittance *= exp(-absorb * seg);
#endif
        }
        q = q + dir * t;
        ivec3 stp = ivec3(ax == 0u ? (dir.x > 0.0f ? 1 : -1) : 0, ax == 1u ? (dir.y > 0.0f ? 1 : -1) : 0,
                           ax == 2u ? (dir.z > 0.0f ? 1 : -1) : 0);
        // Snap the crossed coordinate onto its plane (no drift over many steps).
        if (ax == 0u) q.x = float(c.x + (stp.x > 0 ? 1 : 0));
        if (ax == 1u) q.y = float(c.y + (stp.y > 0 ? 1 : 0));
        if (ax == 2u) q.z = float(c.z + (stp.z > 0 ? 1 : 0));
        ivec3 nc = c + stp;
        vec3 face_out = vec3(stp);  // normal of the crossed face, pointing into the next cell
        // The next voxel's medium (empty or outside the root: the outside medium).
        bool inside_root = nc.x >= 0 && nc.y >= 0 && nc.z >= 0 && nc.x < side && nc.y < side && nc.z < side;
        float n_next = n_out;
        vec3 absorb_next = vec3(0.0f);
        bool occupied = false;
        uint next_attr = cur_attr;
        if (inside_root) {
            rk_svo_hit lk = rk_svo_lookup(buf, tree.desc_words, tree.brick_base_word, tree.depth, uvec3(nc), tree.depth);
            if (lk.found) {
                occupied = true;
                next_attr = lk.attr;
                vec4 m = RK_SVO_MEDIUM_(media, lk.attr);
                n_next = m.x;
                absorb_next = vec3(m.y, m.z, m.w);
            }
        }
        r.steps = it + 1u;
        // An interface where the index changes, and at every re-entry from the look-ahead (an entry
        // counts even into a medium of index n_out, as rk_svo_refract_through counts it).
        if (n_next != n_cur || (occupied && ahead > 0u)) {
            // The surface belongs to the denser side's voxel: the one entered, or the one left.
            // (At a re-entry from the look-ahead the entered voxel is the only one at the face.)
            vec3 nrm = RK_SVO_INTERFACE_NORMAL_(media, (n_next > n_cur || ahead > 0u) ? next_attr : cur_attr, face_out);
            rk_svo_interface f = rk_svo_interface_at(dir, nrm, n_cur, n_next);
            // A substituted (smooth) normal may send the reflected ray on across this face or the
            // refracted one back: then the face itself decides (no zero-length ping-pong).
            if ((f.tir && dot(f.reflected, face_out) > 0.0f) || (!f.tir && dot(f.transmitted, face_out) <= 0.0f))
                f = rk_svo_interface_at(dir, face_out, n_cur, n_next);
            r.interfaces += 1u;
            if (f.tir) {
                dir = f.reflected;  // stays in this cell, now heading back
                if (ahead > 0u) {
                    // Reflected off an object met in the look-ahead (a medium less dense than
                    // n_out): the ray now leaves from that face, and the look-ahead starts again.
                    r.exit_point = tree.root_min + q * voxel;
                    r.exit_normal = -face_out;
                    r.dir = dir;
                    ahead = 1u;
                }
                continue;
            }
            r.transmittance *= 1.0f - f.reflectance;  // the transmitted share of the Fresnel split
            dir = rk_svo_safe_normalize(f.transmitted, dir);
        }
        if (!occupied) {
            if (ahead == 0u) {  // the exit, unless the look-ahead finds a re-entry
                r.exit_point = tree.root_min + q * voxel;
                r.exit_normal = face_out;
                r.dir = dir;
            }
            ahead += 1u;
            if (ahead >= 3u || !inside_root) {
                r.left = true;
                return r;
            }
        } else {
            ahead = 0u;
        }
        c = nc;
        n_cur = n_next;
        absorb = absorb_next;
        cur_attr = next_attr;
    }
    if (ahead > 0u) {  // the bound came during the look-ahead: the ray had left
        r.left = true;
        return r;
    }
    r.exit_point = tree.root_min + q * voxel;
    r.dir = dir;
    return r;
}

/// What a ray does after passing through refractive voxel objects (rk_svo_refract_through).
struct rk_svo_refraction {
    bool hit;             ///< the ray met the octree (false for max_surfaces 0: no object is entered)
    float reflectance;    ///< Fresnel reflectance at the first surface (for the caller's reflection ray)
    vec3 reflect_origin;  ///< that reflection ray
    vec3 reflect_dir;
    vec3 origin;          ///< the ray leaving the objects (or the incoming ray when !hit)
    vec3 dir;
    vec3 transmittance;   ///< product of (1 - R) at every surface crossed and the absorption inside
    uint interfaces;      ///< surfaces crossed (entries, internal changes, exits)
    bool complete;        ///< true: the ray left every object and meets no other (the path is final);
                          ///< false: the march's step bound stopped it inside, or max_surfaces ran out
                          ///< with another object ahead (origin and dir: where it stopped)
};

/// rk_svo_refract_through: follows the refracted path of a ray through every refractive object it
/// meets, up to `max_surfaces` entries (recursion bounded by a parameter; GLSL has none): trace to
/// the next voxel surface, refract in (reflect under TIR), march through the medium (rk_svo_march),
/// refract out, repeat. A re-entry the march follows within a voxel of an exit continues that
/// entry's leg (no new trace, not counted against max_surfaces). It traces at full detail whatever
/// tree.max_level says (the march starts in the hit voxel; a LOD build's cone is not used). The
/// reflection at the first surface is returned for the caller to trace (rk_svo_trace) and weigh by
/// `reflectance`. Media with index == n_outside are transparent (a hollow core and a core of index
/// n_outside give the same path: Wilks's test). Cost: one rk_svo_trace per surface entered, one
/// lookup per voxel crossed inside, and one more trace where max_surfaces runs out.
RK_INLINE rk_svo_refraction rk_svo_refract_through(RK_SVO_BUF buf, rk_svo_tree tree, RK_SVO_MEDIA media, vec3 origin, vec3 dir,
                                                   float n_outside, uint max_surfaces)
{
    tree.max_level = tree.depth;  // the march starts in the hit voxel: full detail
    rk_svo_refraction r;
    r.hit = false;
    r.reflectance = 0.0f;
    r.reflect_origin = origin;
    r.reflect_dir = dir;
    r.origin = origin;
    r.dir = rk_svo_safe_normalize(dir, vec3(0.0f, 0.0f, 1.0f));
    r.transmittance = vec3(1.0f);
    r.interfaces = 0u;
    r.complete = true;
    if (!(max(max(abs(dir.x), abs(dir.y)), abs(dir.z)) >= RK_FLT_MIN)) return r;  // no direction: nothing hit
    for (uint s = 0u; s < max_surfaces; ++s) {
        rk_svo_trace_hit h = rk_svo_trace(buf, tree, r.origin, r.dir, RK_FLT_MAX, vec2(0.0f));
        if (!h.hit) return r;
        vec3 p = rk_svo_hit_point(tree, r.origin, r.dir, h);
        uint hit_attr = rk_svo_trace_attr(buf, tree, h);
        vec4 m = RK_SVO_MEDIUM_(media, hit_attr);
        rk_svo_interface f = rk_svo_interface_at(r.dir, RK_SVO_INTERFACE_NORMAL_(media, hit_attr, h.normal), n_outside, m.x);
        if (!r.hit) {
            r.hit = true;
            r.reflectance = f.reflectance;
            r.reflect_dir = f.reflected;
            r.reflect_origin = rk_svo_secondary_origin(p, h.normal, f.reflected, tree, h.level);
        }
        r.interfaces += 1u;
        if (f.tir) {
            r.dir = f.reflected;
            r.origin = rk_svo_secondary_origin(p, h.normal, r.dir, tree, h.level);
            continue;
        }
        r.transmittance *= 1.0f - f.reflectance;
        vec3 din = rk_svo_safe_normalize(f.transmitted, r.dir);
        // Just inside the face, in the hit voxel (level == depth without LOD).
        rk_svo_march_result mr = rk_svo_march(buf, tree, media, p, din, h.cell, m.x, vec3(m.y, m.z, m.w), n_outside);
        r.interfaces += mr.interfaces;
        r.transmittance *= mr.transmittance;
        r.dir = mr.dir;
        if (!mr.left) {
            r.complete = false;
            r.origin = mr.exit_point;
            return r;
        }
        // Leave along the ray itself (no sideways shift, so a path through empty space between two
        // media follows the same line as one through voxels of index n_outside): far enough to be
        // the secondary offset off the exit face, at most 8 offsets (1/8 voxel) along the ray, whose
        // cells the march's look-ahead has found empty.
        float off = max(rk_svo_voxel_size(tree, tree.depth) * 0.015625f, tree.root_size * 4.76837158e-7f);
        r.origin = mr.exit_point + r.dir * (off / max(dot(r.dir, mr.exit_normal), 0.125f));
    }
    // The budget ran out: the path is final only if nothing lies ahead (one geometry-only trace).
    r.complete = !rk_svo_trace(buf, tree, r.origin, r.dir, RK_FLT_MAX, vec2(0.0f)).hit;
    return r;
}

#endif  // RK_SVO_SECONDARY_GLSL
