// libFuzzer target: iad measurement files (.rxt, skinspec iad, docs/IAD.md), read and every row checked.
#include "formats/rxt_file.hpp"
#include "fuzz/fuzz_input.hpp"
#include "inverse/iad/inverse_adding_doubling.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".rxt");
    skinspec::fuzz::expect_parsed_or_input_error([&] {
        for (const auto& row : skinspec::read_rxt(file).rows) skinspec::check_measurement(row);
    });
    return 0;
}
