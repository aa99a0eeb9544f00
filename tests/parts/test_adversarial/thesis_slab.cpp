// tests/test_adversarial.cpp's configured functions (adversarial_checks.hpp) built with the
// thesis's slab of the polarisation average and the PBR Neutral tone map.
#define RK_FRESNEL_WINDOW_MODE 1
#define RK_WINDOW_GLASS_FRESNEL 0
#define RK_TONEMAP_OPERATOR 5
#include "adversarial_checks.hpp"

TEST(AdversarialConfigured, ThesisSlabPbrNeutral)
{
    static_assert(RK_FRESNEL_WINDOW_MODE == 1 && RK_WINDOW_GLASS_FRESNEL == 0 && RK_TONEMAP_OPERATOR == 5,
                  "this configuration");
    check_configured_functions("window mode 1, exact glass, PBR Neutral");
}
