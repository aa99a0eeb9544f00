// A translation unit of tests/test_odr.cpp: one macro of every configured namespace differs from
// the defaults of test_odr.cpp; the others keep theirs, so that this TU and the defaults differ in
// one macro per namespace (tests/parts/test_odr/second_macros.cpp and third_macros.cpp change the
// rest, likewise).
#define RK_TONEMAP_OPERATOR 1         // Reinhard (AgX look left at 0)
#define RK_IM_COMPOSE_MODE 1          // the thesis's additive window (glass and Fresnel mode left)
#define RK_IM_VARYING_WALLS 1         // walls displaced per index (nudge left)
#define RK_AO_MAX_SAMPLES 16
#define RK_LS_MAX_SAMPLES 32
#define RK_VOL_MAX_STEPS 8
#define RK_RELIEF_MAX_STEPS 4
#define RK_SH_REVERSED_Z 1            // (taps left at 64)
#define RK_SVO_TEXTURE_WIDTH 1024
#define RK_SVO_TRAVERSE_LOD 1         // (iteration bound left)
#define RK_SVO_SECONDARY_FRESNEL_FAST 1  // (absorption and step bound left)
#include "odr_probe.hpp"

OdrProbe odr_probe_other_config() { RK_ODR_PROBE_BODY }
