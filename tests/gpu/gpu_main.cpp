// GPU parity test driver: creates the headless OpenGL 4.5 context (EGL) once, then runs every
// parity_*.cpp case. Exit code 77 (ctest: skipped) when no EGL/GL 4.5 device exists — except with
// CI=true, where a missing device is a failure.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "parity.hpp"

int main(int argc, char** argv)
{
    ::testing::InitGoogleTest(&argc, argv);
    static rkgl::HeadlessContext ctx;
    if (!ctx.create()) {
        return rkgl::no_context_exit("gpu_parity_test", ctx.error());
    }
    std::printf("[parity] renderer: %s\n", ctx.renderer().c_str());
    return RUN_ALL_TESTS();
}
