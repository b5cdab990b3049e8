// One Embree device configuration for every scene gonio builds. Embree picks its kernels by the
// CPU's instruction set, and its AVX-512, AVX2 and SSE kernels round a hit differently (a
// multiple-scattering path then leaves a few ulp elsewhere): capping the kernels at AVX2 gives
// the same bits on every machine that has AVX2 (measured: the quickstart's digest moved by up
// to 2e-5 between AVX-512 and AVX2 kernels, by 1e-5 between AVX2 and SSE4.2).
#pragma once

#include <embree3/rtcore.h>

namespace gonio {

inline constexpr const char* kEmbreeDeviceConfig = "max_isa=avx2";

inline RTCDevice new_embree_device() {
    return rtcNewDevice(kEmbreeDeviceConfig);
}

} // namespace gonio
