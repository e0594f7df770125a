// The standard headers most translation units include, compiled once as a precompiled header
// (CMake's target_precompile_headers, option GRAINFLOW_PCH): the grainflow target's compile at -j2
// took 3 min 57 s with it and 4 min 44 s without. Every source still includes what it uses; this
// list only makes the build faster and changes no code. Library headers stay out: oneTBB, Eigen and
// xsimd bring the compiler's vector intrinsics, which lose their system-header status inside a
// precompiled header, and GCC 12 then warns inside avx512fintrin.h wherever xsimd is inlined (it
// gained 10 s more).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>


