// libFuzzer target: the CSV inputs of skinspec fit-profile, a patch list and a radial profile (the same bytes
// read as both). A file that reads is also fitted, so the fit sees the values the reader lets through.
#include "fuzz/fuzz_input.hpp"
#include "inverse/profile_fit/profile_fit.hpp"
#include "formats/profile_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".csv").string();
    skinspec::ProfileFitOptions options;
    options.dipole.reduced_scattering_per_mm = {0.1, 3.0, 0.1};
    skinspec::fuzz::expect_parsed_or_input_error([&] {
        const auto patches = skinspec::read_patch_list(file);
        if (patches.size() <= 64) skinspec::fit_patches(patches, options);
    });
    skinspec::fuzz::expect_parsed_or_input_error([&] {
        const auto samples = skinspec::read_radial_profile(file);
        skinspec::fit_radial(samples.radii_mm, samples.profile_per_mm2, options);
    });
    return 0;
}
