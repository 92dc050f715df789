// libFuzzer target: material TOML files (presets and user files, docs/MATERIALS.md). A file that parses must
// survive the round trip through to_toml unchanged in meaning: the written text parses again.
#include <cstdlib>

#include "fuzz/fuzz_input.hpp"
#include "materials/material_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".toml");
    skinspec::fuzz::expect_parsed_or_input_error([&] {
        const auto material = skinspec::read_material(file);
        const auto text = skinspec::to_toml(material);
        const auto again = skinspec::fuzz::input_file(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), ".toml");
        try {
            skinspec::read_material(again);
        } catch (const skinspec::InputError&) {
            std::abort();  // what we write we must read back
        }
    });
    return 0;
}
