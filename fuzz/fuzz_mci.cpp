// libFuzzer target: MCML input files (.mci, skinspec mcml, docs/RTE.md).
#include "fuzz/fuzz_input.hpp"
#include "formats/mcml_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".mci");
    skinspec::fuzz::expect_parsed_or_input_error([&] { skinspec::read_mci(file); });
    return 0;
}
