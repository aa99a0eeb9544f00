// svo_features.hpp: the feature macros an octree scene needs. svo_material_needs against materials
// built by hand for each case (a mirror, clear glass, absorbing glass, an absorbing opaque material
// alone, where no ray marches, and beside clear glass, whose refracted rays march through it);
// svo_defines' whole table for several scenes, written out here, not generated; bad input gives an
// empty set and a message.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "raykit/svo_features.hpp"

using namespace raykit;

namespace {

SvoMaterial opaque()
{
    return SvoMaterial();
}
SvoMaterial mirror()
{
    SvoMaterial m;
    m.reflectance = 0.8f;
    return m;
}
SvoMaterial glass(glm::vec3 absorption)
{
    SvoMaterial m;
    m.base_color.a = 0.2f;
    m.ior = 1.5f;
    m.absorption = absorption;
    return m;
}

std::string joined(const std::vector<ShaderDefine>& d)
{
    std::string s;
    for (const ShaderDefine& x : d) s += x.name + "=" + x.value + " ";
    return s;
}

}  // namespace

TEST(SvoFeatures, MaterialNeeds)
{
    struct Case { std::vector<SvoMaterial> m; bool refl, refr, absorb; };
    SvoMaterial opaque_absorbing = opaque();
    opaque_absorbing.absorption = glm::vec3(1.0f);
    const Case cases[] = {
        {{}, false, false, false},
        {{opaque()}, false, false, false},
        {{opaque_absorbing}, false, false, false},  // nothing refracts: no ray marches through it
        {{glass(glm::vec3(0.0f)), opaque_absorbing}, false, true, true},  // refracted rays march into it
        {{mirror()}, true, false, false},
        {{glass(glm::vec3(0.0f))}, false, true, false},
        {{glass(glm::vec3(0.0f, 0.0f, 0.3f))}, false, true, true},
        {{opaque(), mirror(), glass(glm::vec3(0.1f))}, true, true, true},
    };
    for (const Case& c : cases) {
        const SvoMaterialNeeds n = svo_material_needs(c.m);
        EXPECT_EQ(n.reflection, c.refl);
        EXPECT_EQ(n.refraction, c.refr);
        EXPECT_EQ(n.absorption, c.absorb);
    }
}

TEST(SvoFeatures, DefinesForScenes)
{
    Status st;
    // Nothing asked, no materials: every feature at its off value, the iteration bound derived.
    EXPECT_EQ(joined(svo_defines(SvoSceneDesc(), {}, &st)),
              "RK_SVO_TRAVERSE_LOD=0 RK_SVO_TRAVERSE_MAX_ITER=0 RK_SVO_SECONDARY_FRESNEL_FAST=0 "
              "RK_SVO_SECONDARY_ABSORPTION=0 RK_SVO_SECONDARY_MAX_STEPS=4096 RK_SVO_PASS_SHADOWS=0 "
              "RK_SVO_PASS_REFLECTION=0 RK_SVO_PASS_REFRACTION=0 ");
    EXPECT_TRUE(st.ok());
    // LOD and shadows over opaque and mirror materials; fast Fresnel asked but nothing refracts.
    SvoSceneDesc d;
    d.lod = true;
    d.shadows = true;
    d.fast_fresnel = true;
    d.max_iterations = 4096;
    EXPECT_EQ(joined(svo_defines(d, {opaque(), mirror()}, &st)),
              "RK_SVO_TRAVERSE_LOD=1 RK_SVO_TRAVERSE_MAX_ITER=4096 RK_SVO_SECONDARY_FRESNEL_FAST=0 "
              "RK_SVO_SECONDARY_ABSORPTION=0 RK_SVO_SECONDARY_MAX_STEPS=4096 RK_SVO_PASS_SHADOWS=1 "
              "RK_SVO_PASS_REFLECTION=1 RK_SVO_PASS_REFRACTION=0 ");
    // Absorbing glass: refraction, absorption, and the fast Fresnel form now that something refracts.
    d = SvoSceneDesc();
    d.fast_fresnel = true;
    d.max_march_steps = 64;
    EXPECT_EQ(joined(svo_defines(d, {glass(glm::vec3(0.5f, 0.0f, 0.0f))}, &st)),
              "RK_SVO_TRAVERSE_LOD=0 RK_SVO_TRAVERSE_MAX_ITER=0 RK_SVO_SECONDARY_FRESNEL_FAST=1 "
              "RK_SVO_SECONDARY_ABSORPTION=1 RK_SVO_SECONDARY_MAX_STEPS=64 RK_SVO_PASS_SHADOWS=0 "
              "RK_SVO_PASS_REFLECTION=0 RK_SVO_PASS_REFRACTION=1 ");
    // Clear glass: refraction without the exp per voxel.
    EXPECT_EQ(joined(svo_defines(SvoSceneDesc(), {glass(glm::vec3(0.0f))}, &st)),
              "RK_SVO_TRAVERSE_LOD=0 RK_SVO_TRAVERSE_MAX_ITER=0 RK_SVO_SECONDARY_FRESNEL_FAST=0 "
              "RK_SVO_SECONDARY_ABSORPTION=0 RK_SVO_SECONDARY_MAX_STEPS=4096 RK_SVO_PASS_SHADOWS=0 "
              "RK_SVO_PASS_REFLECTION=0 RK_SVO_PASS_REFRACTION=1 ");
}

TEST(SvoFeatures, BadInputGivesNoDefines)
{
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<std::vector<SvoMaterial>> bad_materials;
    for (int field = 0; field < 5; ++field)
        for (float v : {nan, inf, -1.0f}) {
            SvoMaterial m = glass(glm::vec3(0.1f));
            if (field == 0) m.base_color.a = v;
            if (field == 1) m.reflectance = v;
            if (field == 2) m.ior = v;
            if (field == 3) m.absorption.y = v;
            if (field == 4) m.base_color.r = v;
            bad_materials.push_back({opaque(), m});
        }
    SvoMaterial zero_ior = glass(glm::vec3(0.0f));
    zero_ior.ior = 0.0f;
    bad_materials.push_back({zero_ior});
    for (const auto& m : bad_materials) {
        Status st;
        EXPECT_TRUE(svo_defines(SvoSceneDesc(), m, &st).empty());
        EXPECT_FALSE(st.ok());
        EXPECT_NE(st.message.find("svo_defines"), std::string::npos);
    }
    for (uint32_t steps : {0u, (1u << 24) + 1u}) {
        SvoSceneDesc d;
        d.max_march_steps = steps;
        Status st;
        EXPECT_TRUE(svo_defines(d, {}, &st).empty());
        EXPECT_NE(st.message.find("max_march_steps"), std::string::npos);
    }
    SvoSceneDesc d;
    d.max_iterations = (1u << 24) + 1u;
    Status st;
    EXPECT_TRUE(svo_defines(d, {}, &st).empty());
    EXPECT_NE(st.message.find("max_iterations"), std::string::npos);
    // The largest valid values pass.
    d.max_iterations = 1u << 24;
    d.max_march_steps = 1u << 24;
    EXPECT_EQ(svo_defines(d, {}, &st).size(), 8u);
    EXPECT_TRUE(st.ok());
}
