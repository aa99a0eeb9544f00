// tests/test_adversarial.cpp's configured functions (adversarial_checks.hpp) built with N panes per
// polarisation, the fast window-glass Fresnel and the Reinhard tone map.
#define RK_FRESNEL_WINDOW_MODE 3
#define RK_WINDOW_GLASS_FRESNEL 1
#define RK_TONEMAP_OPERATOR 1
#include "adversarial_checks.hpp"

TEST(AdversarialConfigured, NPanesFastReinhard)
{
    static_assert(RK_FRESNEL_WINDOW_MODE == 3 && RK_WINDOW_GLASS_FRESNEL == 1 && RK_TONEMAP_OPERATOR == 1,
                  "this configuration");
    check_configured_functions("window mode 3, fast glass, Reinhard");
}
