#include "spectral/color_management.hpp"

#include <algorithm>

#include <cmath>

#include <fmt/format.h>
#include <OpenColorIO/OpenColorIO.h>

#include "spectral/chromatic_adaptation.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace skinspec {

struct ColorManagement::Impl {
    OCIO::ConstConfigRcPtr config;
    mutable std::mutex mutex;
    mutable std::map<std::string, OCIO::ConstCPUProcessorRcPtr> processors;

    // One CPU processor per transform, built on first use and cached (OCIO processors are thread-safe).
    OCIO::ConstCPUProcessorRcPtr processor(const std::string& key, const OCIO::ConstTransformRcPtr& transform) const {
        std::lock_guard lock(mutex);
        auto& slot = processors[key];
        if (!slot) {
            slot = config->getProcessor(transform)->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                                             OCIO::OPTIMIZATION_LOSSLESS);
        }
        return slot;
    }

    RGB apply(const OCIO::ConstCPUProcessorRcPtr& cpu, const RGB& rgb) const {
        float pixel[3] = {static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2])};
        cpu->applyRGB(pixel);
        return {pixel[0], pixel[1], pixel[2]};
    }
};

ColorManagement::ColorManagement(const std::filesystem::path& config_file)
    : config_file_(config_file), impl_(std::make_unique<Impl>()) {
    try {
        impl_->config = OCIO::Config::CreateFromFile(config_file.string().c_str());
        impl_->config->validate();
    } catch (const OCIO::Exception& e) {
        throw InputError("OpenColorIO config " + config_file.string() + ": " + e.what());
    }
}

ColorManagement::~ColorManagement() = default;

const ColorManagement& ColorManagement::builtin() {
    static const ColorManagement cm(data_file("ocio/config.ocio"));
    return cm;
}

XYZ ColorManagement::reference_white() { return white_from_chromaticity({0.3127, 0.3290}); }

std::vector<std::string> ColorManagement::color_spaces() const {
    std::vector<std::string> names;
    for (int i = 0; i < impl_->config->getNumColorSpaces(); ++i) names.emplace_back(impl_->config->getColorSpaceNameByIndex(i));
    return names;
}

std::vector<std::string> ColorManagement::displays() const {
    std::vector<std::string> names;
    for (int i = 0; i < impl_->config->getNumDisplays(); ++i) names.emplace_back(impl_->config->getDisplay(i));
    return names;
}

std::vector<std::string> ColorManagement::views(std::string_view display) const {
    const std::string d(display);
    std::vector<std::string> names;
    for (int i = 0; i < impl_->config->getNumViews(d.c_str()); ++i) names.emplace_back(impl_->config->getView(d.c_str(), i));
    return names;
}

void ColorManagement::check_display_view(std::string_view display, std::string_view view) const {
    const auto join = [](const std::vector<std::string>& names) {
        std::string out;
        for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
        return out;
    };
    const auto all = displays();
    if (std::find(all.begin(), all.end(), display) == all.end()) {
        throw InputError("--display: '" + std::string(display) + "' is not a display of the config (allowed: " + join(all) + ")");
    }
    const auto own = views(display);
    if (std::find(own.begin(), own.end(), view) == own.end()) {
        throw InputError("--view: '" + std::string(view) + "' is not a view of display '" + std::string(display) + "' (allowed: " + join(own) + ")");
    }
}

std::string ColorManagement::canonical_space(std::string_view name, std::string_view what) const {
    const std::string n(name);
    if (const auto cs = impl_->config->getColorSpace(n.c_str())) return cs->getName();
    std::string allowed;
    for (const auto& s : color_spaces()) allowed += (allowed.empty() ? "" : ", ") + s;
    throw InputError(std::string(what) + ": '" + n + "' is not a colour space of " + config_file_.string() +
                     " (allowed: " + allowed + ")");
}

RGB ColorManagement::from_xyz(const XYZ& xyz, const XYZ& white, std::string_view space) const {
    const XYZ adapted = bradford_adapt(xyz, white, reference_white());
    return convert({adapted.X, adapted.Y, adapted.Z}, OCIO::ROLE_REFERENCE, space);
}

// One cached CPU processor per (source, destination) colour space pair.
OCIO::ConstCPUProcessorRcPtr colorspace_processor(const ColorManagement& cm, const ColorManagement::Impl& impl,
                                                  std::string_view from_space, std::string_view to_space) {
    const std::string from = cm.canonical_space(from_space, "source colour space");
    const std::string to = cm.canonical_space(to_space, "destination colour space");
    auto transform = OCIO::ColorSpaceTransform::Create();
    transform->setSrc(from.c_str());
    transform->setDst(to.c_str());
    return impl.processor("cs:" + from + "\n" + to, transform);
}

// One cached CPU processor per (source space, display, view).
OCIO::ConstCPUProcessorRcPtr display_processor(const ColorManagement& cm, const ColorManagement::Impl& impl,
                                               std::string_view from_space, std::string_view display, std::string_view view) {
    const std::string from = cm.canonical_space(from_space, "source colour space");
    const std::string d(display);
    const std::string v(view);
    auto transform = OCIO::DisplayViewTransform::Create();
    transform->setSrc(from.c_str());
    transform->setDisplay(d.c_str());
    transform->setView(v.c_str());
    try {
        return impl.processor("dv:" + from + "\n" + d + "\n" + v, transform);
    } catch (const OCIO::Exception& e) {
        throw InputError("display '" + d + "', view '" + v + "': " + e.what());
    }
}

namespace {

void apply_packed(const OCIO::ConstCPUProcessorRcPtr& cpu, std::vector<float>& rgb) {
    if (rgb.empty()) return;
    OCIO::PackedImageDesc image(rgb.data(), static_cast<long>(rgb.size() / 3), 1, 3);
    cpu->apply(image);
}

}  // namespace

RGB ColorManagement::convert(const RGB& rgb, std::string_view from_space, std::string_view to_space) const {
    return impl_->apply(colorspace_processor(*this, *impl_, from_space, to_space), rgb);
}

void ColorManagement::convert_pixels(std::vector<float>& rgb, std::string_view from_space, std::string_view to_space) const {
    apply_packed(colorspace_processor(*this, *impl_, from_space, to_space), rgb);
}

RGB ColorManagement::display_view(const RGB& rgb, std::string_view from_space, std::string_view display,
                                  std::string_view view) const {
    return impl_->apply(display_processor(*this, *impl_, from_space, display, view), rgb);
}

void ColorManagement::display_view_pixels(std::vector<float>& rgb, std::string_view from_space, std::string_view display,
                                          std::string_view view) const {
    apply_packed(display_processor(*this, *impl_, from_space, display, view), rgb);
}

std::string hex_rgb8(const RGB& encoded) {
    std::string out = "#";
    for (const double c : encoded) out += fmt::format("{:02X}", static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)));
    return out;
}

}  // namespace skinspec
