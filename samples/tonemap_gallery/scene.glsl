// raykit sample — tonemap_gallery/scene.glsl: the procedural HDR scene that every panel of the
// gallery renders (included by gallery.frag; sample code, not part of the shared GLSL/C++ dialect).
//
// A small analytic ray tracer: a sky gradient with a low sun (disk and aureole) in the top-right
// corner, a chequered ground plane, and a row of eight spheres on it, from left to right: diffuse
// black (albedo 0.03), grey (0.18) and white (0.85), a red sphere under a clear coat, and four
// emissive orbs in saturated red, green, blue and yellow of equal luminance, 40x brighter at their
// cores than at their rims (each orb is itself a ramp into the highlights), lighting the ground
// under them. The sun is ahead of the camera: the spheres are lit from behind, right, and throw
// long shadows towards the viewer.
//
// Units: scene-referred linear Rec.709, luminance in an arbitrary unit in which the sky is ~0.2
// (zenith) to ~1 (horizon), the white sphere facing the sun ~6.5, the orbs 1.5 (rim) to 60 (core),
// the sun's aureole 1..100 and its disk 1.8e4; contact shadows go down to ~2e-3.
#ifndef GALLERY_SCENE_GLSL
#define GALLERY_SCENE_GLSL

#include "raykit/color.glsl"

const float kScenePi = 3.14159265;

// Towards the sun: 24 deg right of the view direction, 8 deg up (in the view's top-right corner).
const vec3 kSunDir = vec3(sin(radians(24.0)) * cos(radians(8.0)), sin(radians(8.0)),
                          cos(radians(24.0)) * cos(radians(8.0)));
const vec3 kSunTint = vec3(1.0, 0.88, 0.72);              // late afternoon; luminance ~0.89
const float kSunRadius = 0.022;                           // radians (the real sun: 0.0047)
const float kSunDiskRadiance = 2.0e4;
const float kSunIrradiance = 24.0;                        // on a surface facing the sun
const int kSpheres = 8;
const float kSphereRadius = 0.42;

// The saturated hues of the orbs and of the colour ramps, scaled to luminance 1 by scene_hue().
const vec3 kHues[4] = vec3[4](vec3(1.0, 0.06, 0.03),   // red
                              vec3(0.05, 1.0, 0.08),   // green
                              vec3(0.06, 0.16, 1.0),   // blue
                              vec3(1.0, 0.72, 0.02));  // yellow
vec3 scene_hue(int i) { return kHues[i] / rk_luminance(kHues[i]); }

// Emissive orbs (spheres 4..7): luminance at the rim, and the factor to the core's.
const float kOrbRim = 1.5;
const float kOrbCoreGain = 40.0;

vec3 sphere_center(int i) { return vec3(-3.5 + float(i), kSphereRadius, 0.0); }

// Ray / sphere: distance to the first hit in front of ro, or -1.
float hit_sphere(vec3 ro, vec3 rd, vec3 c, float r)
{
    vec3 oc = ro - c;
    float b = dot(oc, rd);
    float h = b * b - (dot(oc, oc) - r * r);
    if (h < 0.0) return -1.0;
    float t = -b - sqrt(h);
    return t > 1e-4 ? t : -1.0;
}

// Sky radiance in direction d: a zenith-to-horizon gradient, the sun's aureole and (with disk) its disk.
vec3 sky(vec3 d, bool disk)
{
    float h = clamp(d.y, 0.0, 1.0);
    vec3 zenith = vec3(0.06, 0.16, 0.78);
    vec3 horizon = vec3(0.62, 0.76, 1.05) * 1.3;
    vec3 c = mix(horizon, zenith, 1.0 - exp(-h * 5.0));
    float ang = acos(clamp(dot(d, kSunDir), -1.0, 1.0));
    c += kSunTint * (150.0 * exp(-ang / 0.02) + 6.0 * exp(-ang / 0.1) + 0.6 * exp(-ang / 0.35));
    if (disk && ang < kSunRadius) c += kSunTint * kSunDiskRadiance;
    return c;
}

// The clear coat's mirror image of the sky, with the sun's disk blurred to a highlight of the same
// energy (a gloss lobe of 0.05 rad).
vec3 sky_glossy(vec3 d)
{
    float ang = acos(clamp(dot(d, kSunDir), -1.0, 1.0));
    float lobe = 0.05;
    float k = (kSunRadius * kSunRadius) / (lobe * lobe);
    return sky(d, false) + kSunTint * kSunDiskRadiance * k * exp(-(ang * ang) / (lobe * lobe));
}

// Fraction of the sun's disk visible from p (soft shadows of the spheres).
float sun_visibility(vec3 p)
{
    float v = 1.0;
    for (int i = 0; i < kSpheres; ++i) {
        vec3 oc = sphere_center(i) - p;
        float along = dot(oc, kSunDir);
        if (along <= 0.0) continue;
        float miss = sqrt(max(dot(oc, oc) - along * along, 0.0)) - kSphereRadius;  // closest approach
        v *= smoothstep(-kSunRadius, kSunRadius, miss / along);
    }
    return v;
}

// Sky visibility at p with normal n: the spheres' analytic occlusion (a sphere of radius r at
// distance l covers (r / l)^2 cos of the hemisphere's cosine-weighted area).
float sky_visibility(vec3 p, vec3 n, int self)
{
    float occ = 0.0;
    for (int i = 0; i < kSpheres; ++i) {
        if (i == self) continue;
        vec3 d = sphere_center(i) - p;
        float l = length(d);
        occ += max(dot(n, d / l), 0.0) * (kSphereRadius * kSphereRadius) / (l * l);
    }
    return clamp(1.0 - occ, 0.0, 1.0);
}

// Orb i's radiance seen along view direction v at normal n: rim luminance at grazing view,
// kOrbCoreGain times that facing the viewer.
vec3 orb_radiance(int i, vec3 n, vec3 v)
{
    float f = max(dot(n, -v), 0.0);
    return scene_hue(i) * kOrbRim * (1.0 + (kOrbCoreGain - 1.0) * f * f * f);
}

// Irradiance at p (normal n) from the orbs, each taken as a sphere light of its mean radiance.
vec3 orb_irradiance(vec3 p, vec3 n, int self)
{
    vec3 e = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        if (i + 4 == self) continue;
        vec3 d = sphere_center(i + 4) - p;
        float l2 = dot(d, d);
        float mean = kOrbRim * (1.0 + (kOrbCoreGain - 1.0) * 0.4);  // mean of f^3 over the disk: 0.4
        e += scene_hue(i) * mean * kScenePi * (kSphereRadius * kSphereRadius) / l2 *
             max(dot(n, d * inversesqrt(l2)), 0.0);
    }
    return e;
}

// Diffuse shading: sun (with shadow), sky (with occlusion) and the orbs' light.
vec3 shade_diffuse(vec3 p, vec3 n, vec3 albedo, int self)
{
    vec3 sky_e = vec3(0.55, 0.72, 1.0) * 2.6 * (0.55 + 0.45 * n.y) * sky_visibility(p, n, self);
    vec3 sun_e = kSunTint * kSunIrradiance * max(dot(n, kSunDir), 0.0) * sun_visibility(p + n * 1e-3);
    return albedo / kScenePi * (sky_e + sun_e + orb_irradiance(p, n, self));
}

// The camera: eye above the ground looking along +z, slightly down; uv in [0, 1]^2, (0, 0) at the
// top-left of the view, aspect = width / height.
void scene_camera(vec2 uv, float aspect, out vec3 ro, out vec3 rd)
{
    ro = vec3(0.0, 1.7, -6.8);
    vec3 fwd = vec3(0.0, -sin(radians(7.0)), cos(radians(7.0)));  // 7 deg down
    vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), fwd));
    vec3 up = cross(fwd, right);
    float t = tan(radians(40.0) * 0.5);  // vertical field of view 40 deg
    vec2 ndc = vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    rd = normalize(fwd + right * (ndc.x * t * aspect) + up * (ndc.y * t));
}

// Scene radiance (linear Rec.709) at view position uv.
vec3 scene_radiance(vec2 uv, float aspect)
{
    vec3 ro, rd;
    scene_camera(uv, aspect, ro, rd);

    float best = 1e30;
    int id = -1;
    for (int i = 0; i < kSpheres; ++i) {
        float t = hit_sphere(ro, rd, sphere_center(i), kSphereRadius);
        if (t > 0.0 && t < best) {
            best = t;
            id = i;
        }
    }
    float tg = rd.y < 0.0 ? -ro.y / rd.y : 1e30;
    if (id < 0 && tg >= 1e30) return sky(rd, true);

    if (id >= 0 && best < tg) {
        vec3 p = ro + rd * best;
        vec3 n = normalize(p - sphere_center(id));
        if (id >= 4) return orb_radiance(id - 4, n, rd);
        if (id == 3) {  // glossy red: diffuse base under a clear coat (Schlick, f0 = 0.04)
            float f = 0.04 + 0.96 * pow(1.0 - max(dot(n, -rd), 0.0), 5.0);
            vec3 refl = reflect(rd, n);
            vec3 coat = refl.y > 0.0 ? sky_glossy(refl) * sun_visibility(p + n * 1e-3)
                                     : vec3(0.2) * kSunIrradiance / kScenePi * 0.25;  // the ground, roughly
            return (1.0 - f) * shade_diffuse(p, n, vec3(0.62, 0.05, 0.04), id) + f * coat;
        }
        float a = id == 0 ? 0.03 : (id == 1 ? 0.18 : 0.85);
        return shade_diffuse(p, n, vec3(a), id);
    }

    // Ground: a faint 1 m chequer (its contrast fading with distance, before it aliases), and a
    // little haze towards the horizon.
    vec3 p = ro + rd * tg;
    vec2 cell = floor(p.xz);
    float check = mod(cell.x + cell.y, 2.0) - 0.5;
    vec3 albedo = vec3(0.26, 0.23, 0.185) + vec3(0.08, 0.08, 0.07) * check * exp(-max(tg - 6.0, 0.0) * 0.12);
    vec3 c = shade_diffuse(p, vec3(0.0, 1.0, 0.0), albedo, -1);
    float haze = 1.0 - exp(-max(tg - 8.0, 0.0) * 0.02);
    return mix(c, sky(vec3(rd.x, 0.0, rd.z) / max(length(rd.xz), 1e-6), false), haze);
}

#endif  // GALLERY_SCENE_GLSL
