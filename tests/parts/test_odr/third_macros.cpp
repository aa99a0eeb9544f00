// A translation unit of tests/test_odr.cpp: the third macro of the configured namespaces that name
// three (rk_im_window's, svo_secondary.hpp's) differs from the defaults of test_odr.cpp; the others
// keep theirs.
#define RK_FRESNEL_WINDOW_MODE 0         // single surface (rk_im_window: Fresnel compose, exact glass)
#define RK_SVO_SECONDARY_ABSORPTION 0    // (exact Fresnel, default step bound)
#include "odr_probe.hpp"

OdrProbe odr_probe_third_macros() { RK_ODR_PROBE_BODY }
