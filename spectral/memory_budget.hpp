#pragma once
// Memory a request may use, checked before allocating (a 240 x 240 swatch under a 1 GB limit computed for 85 s,
// then ended in "internal error: std::bad_alloc").
#include <string_view>

namespace skinspec {

// Bytes this process can still allocate: the smaller of the system's available memory (/proc/meminfo MemAvailable)
// and what the address-space limit (RLIMIT_AS) leaves above the current size; +inf when neither is known.
double available_memory_bytes();

// InputError "WHAT needs about X GB of memory, more than the Y GB available (HINT)" when `bytes` exceeds it.
void check_memory(double bytes, std::string_view what, std::string_view hint);

}  // namespace skinspec
