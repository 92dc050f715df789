#pragma once
// Tests of the SIMD walks: runs a scope on one instruction set (Highway's test hook) and restores the machine's own
// when the scope ends.
#include <cstdint>

#include <hwy/targets.h>

namespace skinspec::testing {

struct ForcedTarget {
    explicit ForcedTarget(std::int64_t target) { hwy::SetSupportedTargetsForTest(target); }
    ~ForcedTarget() { hwy::SetSupportedTargetsForTest(0); }
    ForcedTarget(const ForcedTarget&) = delete;
    ForcedTarget& operator=(const ForcedTarget&) = delete;
};

}  // namespace skinspec::testing
