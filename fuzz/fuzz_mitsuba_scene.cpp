// libFuzzer target: Mitsuba 3 scene files as skinspec export mitsuba writes them (formats/mitsuba_scene.hpp).
#include "fuzz/fuzz_input.hpp"
#include "formats/mitsuba_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".xml");
    skinspec::fuzz::expect_parsed_or_input_error([&] { skinspec::read_mitsuba_scene(file); });
    return 0;
}
