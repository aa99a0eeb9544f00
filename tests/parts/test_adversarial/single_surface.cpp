// tests/test_adversarial.cpp's configured functions (adversarial_checks.hpp) built with a single
// surface, the fast window-glass Fresnel and AgX with the punchy look.
#define RK_FRESNEL_WINDOW_MODE 0
#define RK_WINDOW_GLASS_FRESNEL 1
#define RK_TONEMAP_OPERATOR 4
#define RK_AGX_LOOK 2
#include "adversarial_checks.hpp"

TEST(AdversarialConfigured, SingleSurfaceFastAgxPunchy)
{
    static_assert(RK_FRESNEL_WINDOW_MODE == 0 && RK_WINDOW_GLASS_FRESNEL == 1 && RK_AGX_LOOK == 2,
                  "this configuration");
    check_configured_functions("window mode 0, fast glass, AgX punchy");
}
