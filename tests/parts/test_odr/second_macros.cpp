// A translation unit of tests/test_odr.cpp: a second macro of every configured namespace that names
// two or more differs from the defaults of test_odr.cpp (one that other_config.cpp leaves alone);
// the others keep theirs.
#define RK_AGX_LOOK 1                    // golden (the AgX operator is the default)
#define RK_WINDOW_GLASS_FRESNEL 1        // fast window glass (Fresnel mode and compose mode left)
#define RK_IM_NUDGE 0.25f                // (regular walls)
#define RK_IM_NUDGE_TAG 2em2
#define RK_SH_MAX_TAPS 5                 // (usual depth)
#define RK_SVO_TRAVERSE_MAX_ITER 2       // (no level of detail)
#define RK_SVO_SECONDARY_MAX_STEPS 1     // (exact Fresnel, absorption)
#include "odr_probe.hpp"

OdrProbe odr_probe_second_macros() { RK_ODR_PROBE_BODY }
