// libFuzzer target: spectrum CSV files (skinspec color, docs/DATA_FORMAT.md), read with the default rules
// and with values over one allowed.
#include "fuzz/fuzz_input.hpp"
#include "formats/spectrum_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".csv");
    skinspec::fuzz::expect_parsed_or_input_error([&] { skinspec::read_spectrum_csv(file); });
    skinspec::SpectrumFileRules over_one;
    over_one.allow_over_one = true;
    skinspec::fuzz::expect_parsed_or_input_error([&] { skinspec::read_spectrum_csv(file, over_one); });
    return 0;
}
