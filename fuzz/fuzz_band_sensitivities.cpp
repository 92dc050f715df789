// libFuzzer target: the band sensitivity CSV of skinspec fit-image --bands. A file that reads also weighs the model's
// wavelength grid, so the weights see the values the reader lets through.
#include <cmath>
#include <stdexcept>

#include "fuzz/fuzz_input.hpp"
#include "inverse/image_fit/band_sensitivities.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = skinspec::fuzz::input_file(data, size, ".csv");
    skinspec::fuzz::expect_parsed_or_input_error([&] {
        const auto bands = skinspec::read_band_sensitivities(file);
        std::vector<double> nm;
        for (double l = 380.0; l <= 780.0; l += 5.0) nm.push_back(l);
        for (const auto& w : skinspec::band_weights(bands, nm)) {
            double sum = 0.0;
            for (const double x : w) {
                if (!(std::isfinite(x) && x >= 0.0)) throw std::logic_error("band weight not finite and >= 0");
                sum += x;
            }
            if (std::abs(sum - 1.0) > 1e-9) throw std::logic_error("band weights do not sum to 1");
        }
    });
    return 0;
}
