// libFuzzer target: measured spectra to fit (skinspec fit-spectrum, formats/measured_spectra.hpp).
#include "formats/measured_spectra.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".csv");
    skinspec::fuzz::expect_parsed_or_input_error([&] { skinspec::read_measured_spectra(file); });
    return 0;
}
