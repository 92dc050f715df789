// libFuzzer target: pbrt-v4 scene files as skinspec export pbrt writes them (formats/pbrt_scene.hpp).
#include "fuzz/fuzz_input.hpp"
#include "formats/pbrt_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".pbrt");
    skinspec::fuzz::expect_parsed_or_input_error([&] { skinspec::read_pbrt_scene(file); });
    return 0;
}
