// libFuzzer target: the image pair (and mask) of skinspec fit-profile's planar input. The bytes choose the
// size (1-16 px a side), channel counts, pitch and every float (NaN, infinities and denormals included); the
// images are written as OpenEXR and go through the same reader and fit as the command. Fuzzing OpenEXR's own
// decoder is left to OpenEXR: the files here are well-formed, their contents are not.
#include <cstring>

#include "fuzz/fuzz_input.hpp"
#include "inverse/profile_fit/profile_fit.hpp"
#include "formats/profile_inputs.hpp"
#include "spectral/chart_image.hpp"

namespace {

struct Bytes {
    const std::uint8_t* data;
    std::size_t size;
    std::size_t at = 0;
    template <typename T>
    T next() {
        T value{};
        if (at + sizeof(T) <= size) std::memcpy(&value, data + at, sizeof(T));
        at += sizeof(T);
        return value;
    }
};

skinspec::DataImage image(Bytes& bytes, int width, int height, int channels) {
    skinspec::DataImage result{width, height, channels, {}, true, {}, {}};
    for (int c = 0; c < channels; ++c) result.channel_names.push_back(std::string(1, "RGBA"[c]));
    for (int i = 0; i < width * height * channels; ++i) result.values.push_back(bytes.next<float>());
    return result;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes bytes{data, size};
    const int width = 1 + bytes.next<std::uint8_t>() % 16;
    const int height = 1 + bytes.next<std::uint8_t>() % 16;
    const std::uint8_t shape = bytes.next<std::uint8_t>();
    const int channels_e = 1 + shape % 4, channels_l = 1 + (shape / 4) % 4;
    const bool mask = (shape & 16) != 0;
    const bool size_mismatch = (shape & 32) != 0;
    const double pitch_mm = bytes.next<double>();
    const auto dir = std::filesystem::temp_directory_path();
    const auto tag = std::to_string(::getpid());
    skinspec::PlanarInputs inputs{(dir / ("skinspec_fuzz_e_" + tag + ".exr")).string(), (dir / ("skinspec_fuzz_l_" + tag + ".exr")).string(),
                                  mask ? (dir / ("skinspec_fuzz_m_" + tag + ".exr")).string() : std::string(), pitch_mm};
    skinspec::write_data_image(inputs.irradiance, image(bytes, width, height, channels_e), {});
    skinspec::write_data_image(inputs.exitance, image(bytes, width, size_mismatch ? height % 16 + 1 : height, channels_l), {});
    if (mask) skinspec::write_data_image(inputs.mask, image(bytes, width, height, 1), {});
    skinspec::ProfileFitOptions options;
    options.dipole.reduced_scattering_per_mm = {0.1, 3.0, 0.1};
    skinspec::fuzz::expect_parsed_or_input_error([&] {
        std::vector<std::string> names;
        for (const auto& scene : skinspec::read_planar_scenes(inputs, names)) skinspec::fit_planar(scene, options);
    });
    return 0;
}
