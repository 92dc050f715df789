#include "formats/mitsuba_scene.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <pugixml.hpp>

#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double quad_half_side_mm = 1000.0;  // as the pbrt scene: far beyond the skin's diffusion length

std::string joined(const std::vector<double>& values, const char* separator) {
    std::string out;
    for (const double v : values) {
        if (!out.empty()) out += separator;
        out += format_number(v);
    }
    return out;
}

pugi::xml_node child(pugi::xml_node parent, const char* tag, std::initializer_list<std::pair<const char*, std::string>> attributes) {
    auto node = parent.append_child(tag);
    for (const auto& [k, v] : attributes) node.append_attribute(k) = v.c_str();
    return node;
}

// Mitsuba's medium takes sigma_t and albedo: sigma_t = sigma_a + sigma_s, albedo = sigma_s / sigma_t. sigma_t is
// written divided by its peak, which goes to the medium's `scale` (Mitsuba 3 homogeneous medium: "scale applied to
// sigma_t"): Mitsuba's RGB values must lie in [0, 1] (a value above throws) and its *_rgb variants clamp spectra to
// [0, 1], so 1/mm coefficients of 100 and more must be scaled to load at all.
struct Extinction {
    std::vector<double> sigma_t_relative;  // sigma_t / scale, at most 1
    std::vector<double> albedo;
    double scale = 1.0;  // [1/mm]
};
Extinction extinction_albedo(const RendererLayer& l) {
    Extinction e;
    std::vector<double> t;
    for (std::size_t i = 0; i < l.sigma_a_per_mm.size(); ++i) {
        t.push_back(l.sigma_a_per_mm[i] + l.sigma_s_per_mm[i]);
        e.albedo.push_back(t.back() > 0.0 ? l.sigma_s_per_mm[i] / t.back() : 0.0);
    }
    const double peak = t.empty() ? 0.0 : *std::max_element(t.begin(), t.end());
    if (peak > 0.0) e.scale = peak;
    for (const double v : t) e.sigma_t_relative.push_back(v / e.scale);
    return e;
}

void spectrum_node(pugi::xml_node medium, const RendererMedia& media, const std::filesystem::path& scene, const RendererLayer& layer,
                   const std::string& quantity, const std::vector<double>& values) {
    if (media.rgb) {
        child(medium, "rgb", {{"name", quantity}, {"value", joined(values, ", ")}});
        return;
    }
    child(medium, "spectrum", {{"name", quantity}, {"filename", spectrum_file_reference(scene, layer.name, quantity)}});
}

void rectangle(pugi::xml_node scene, double z_mm, const std::string& interior, const std::string& exterior, std::optional<std::pair<double, double>> iors,
               bool reflector) {
    auto shape = child(scene, "shape", {{"type", "rectangle"}});
    auto to_world = child(shape, "transform", {{"name", "to_world"}});
    child(to_world, "scale", {{"x", format_number(quad_half_side_mm)}, {"y", format_number(quad_half_side_mm)}});
    child(to_world, "translate", {{"z", format_number(z_mm)}});
    if (reflector) {
        auto bsdf = child(shape, "bsdf", {{"type", "diffuse"}});
        child(bsdf, "rgb", {{"name", "reflectance"}, {"value", "1, 1, 1"}});
    } else if (iors && iors->first != iors->second) {
        auto bsdf = child(shape, "bsdf", {{"type", "dielectric"}});
        child(bsdf, "float", {{"name", "int_ior"}, {"value", format_number(iors->first)}});
        child(bsdf, "float", {{"name", "ext_ior"}, {"value", format_number(iors->second)}});
    } else {
        child(shape, "bsdf", {{"type", "null"}});
    }
    if (!interior.empty()) child(shape, "ref", {{"name", "interior"}, {"id", interior}});
    if (!exterior.empty()) child(shape, "ref", {{"name", "exterior"}, {"id", exterior}});
}

double number_attribute(pugi::xml_node node, const char* attribute, const std::string& where) {
    const auto text = std::string(node.attribute(attribute).as_string());
    const auto v = parse_double(trim(text));
    if (!v) throw InputError(where + ": '" + text + "' is not a number");
    return *v;
}

pugi::xml_node named(pugi::xml_node parent, const char* name) {
    for (auto c : parent.children()) {
        if (std::string(c.attribute("name").as_string()) == name) return c;
    }
    return {};
}

}  // namespace

std::vector<std::filesystem::path> mitsuba_scene_files(const RendererMedia& media, const std::filesystem::path& scene) {
    return scene_files(media, scene, {"sigma_t", "albedo"});
}

void write_mitsuba_scene(const RendererMedia& media, const std::filesystem::path& scene_file, std::string_view note) {
    if (!media.rgb) {
        std::filesystem::create_directories(spectra_folder(scene_file));
        for (const auto& l : media.layers) {
            const auto e = extinction_albedo(l);
            write_spd_file(spectrum_file_path(scene_file, l.name, "sigma_t"), media.wavelengths_nm, e.sigma_t_relative,
                           fmt::format("skinspec {}: {} layer {} extinction coefficient sigma_t = sigma_a + sigma_s divided by the medium's scale {} [1/mm]",
                                       version, media.material, l.name, format_number(e.scale)));
            write_spd_file(spectrum_file_path(scene_file, l.name, "albedo"), media.wavelengths_nm, e.albedo,
                           fmt::format("skinspec {}: {} layer {} single-scattering albedo sigma_s / sigma_t [unitless]", version, media.material, l.name));
        }
    }
    pugi::xml_document doc;
    double depth_mm = 0.0;
    for (const auto& l : media.layers) depth_mm += l.thickness_mm;
    doc.append_child(pugi::node_comment)
        .set_value(fmt::format(" skinspec {}: {} as Mitsuba 3 media under uniform D65 light, seen straight down. Scene units mm; sigma_t in 1/mm as written times "
                               "the medium's scale. {} Phase functions at {} nm. Layers top to bottom from z = 0 (total {} mm). {}",
                               version, media.material,
                               media.rgb ? fmt::format("RGB media: the coefficients at {} nm taken as R, G, B.", joined(media.wavelengths_nm, ", "))
                                         : fmt::format("Spectral media: {} wavelengths, {}-{} nm (spectral variants).", media.wavelengths_nm.size(),
                                                       format_number(media.wavelengths_nm.front()), format_number(media.wavelengths_nm.back())),
                               fmt::format("{:.6g}", media.phase_wavelength_nm), fmt::format("{:.6g}", depth_mm), note.empty() ? std::string() : std::string(note) + " ")
                       .c_str());
    auto scene = child(doc, "scene", {{"version", "3.0.0"}});
    auto integrator = child(scene, "integrator", {{"type", "volpath"}});
    child(integrator, "integer", {{"name", "max_depth"}, {"value", "-1"}});
    // A light a path tracer reaches through the specular interfaces (a directional one is not, issue 65): a uniform
    // environment; the orthographic camera sees [-1, 1]^2 scaled, scene_view_mm of the slab.
    auto sensor = child(scene, "sensor", {{"type", "orthographic"}});
    auto camera = child(sensor, "transform", {{"name", "to_world"}});
    const auto half_view = format_number(scene_view_mm / 2);
    child(camera, "scale", {{"x", half_view}, {"y", half_view}});
    child(camera, "lookat", {{"origin", "0, 0, 50"}, {"target", "0, 0, 0"}, {"up", "0, 1, 0"}});
    auto sampler = child(sensor, "sampler", {{"type", "independent"}});
    child(sampler, "integer", {{"name", "sample_count"}, {"value", std::to_string(scene_samples_per_pixel)}});
    auto film = child(sensor, "film", {{"type", "hdrfilm"}});
    child(film, "integer", {{"name", "width"}, {"value", std::to_string(scene_pixels)}});
    child(film, "integer", {{"name", "height"}, {"value", std::to_string(scene_pixels)}});
    auto light = child(scene, "emitter", {{"type", "constant"}});
    child(light, "spectrum", {{"name", "radiance"}, {"type", "d65"}});

    for (const auto& l : media.layers) {
        auto medium = child(scene, "medium", {{"type", "homogeneous"}, {"id", l.name}});
        const auto e = extinction_albedo(l);
        spectrum_node(medium, media, scene_file, l, "sigma_t", e.sigma_t_relative);
        spectrum_node(medium, media, scene_file, l, "albedo", e.albedo);
        child(medium, "float", {{"name", "scale"}, {"value", format_number(e.scale)}});
        if (l.phase.kind == RendererPhase::Kind::isotropic) {
            child(medium, "phase", {{"type", "isotropic"}});
        } else if (l.phase.kind == RendererPhase::Kind::tabulated) {
            auto phase = child(medium, "phase", {{"type", "tabphase"}});
            child(phase, "string", {{"name", "values"}, {"value", joined(l.phase.values, ", ")}});
        } else {
            auto phase = child(medium, "phase", {{"type", "hg"}});
            child(phase, "float", {{"name", "g"}, {"value", format_number(l.phase.g)}});
        }
    }
    double z = 0.0, above = media.above_refractive_index;
    std::string outside;
    for (const auto& l : media.layers) {
        rectangle(scene, z, l.name, outside, std::pair{l.refractive_index, above}, false);
        z -= l.thickness_mm;
        above = l.refractive_index;
        outside = l.name;
    }
    rectangle(scene, z, "", outside, std::pair{media.below_refractive_index, above}, media.bottom_reflector);
    std::ostringstream text;
    doc.save(text, "    ");
    write_text_file(scene_file, text.str(), true);
}

RendererMedia read_mitsuba_scene(const std::filesystem::path& scene_file) {
    pugi::xml_document doc;
    const auto file = scene_file.string();
    const auto parsed = doc.load_file(scene_file.c_str());
    if (!parsed) throw InputError("Mitsuba scene " + file + ": " + parsed.description() + " at byte " + std::to_string(parsed.offset));
    const auto scene = doc.child("scene");
    if (!scene) throw InputError(file + ": no <scene> element");
    RendererMedia media;
    std::map<std::string, RendererLayer> by_id;
    const auto values_of = [&](pugi::xml_node medium, const char* quantity, const std::string& id) {
        const auto node = named(medium, quantity);
        const auto where = file + ": medium " + id + " " + quantity;
        if (!node) throw InputError(where + " is missing");
        if (std::string(node.name()) == "rgb") {
            media.rgb = true;
            std::vector<double> out;
            for (const auto field : split_fields(node.attribute("value").as_string())) {
                const auto v = parse_double(field);
                if (!v) throw InputError(where + ": '" + std::string(field) + "' is not a number");
                out.push_back(*v);
            }
            return out;
        }
        if (!node.attribute("filename")) throw InputError(where + ": expected a spectrum file or rgb");
        auto [nm, values] = read_spd_file(scene_file.parent_path() / node.attribute("filename").as_string());
        media.wavelengths_nm = nm;
        return values;
    };
    for (const auto medium : scene.children("medium")) {
        RendererLayer layer;
        layer.name = medium.attribute("id").as_string();
        const auto t = values_of(medium, "sigma_t", layer.name);
        const auto a = values_of(medium, "albedo", layer.name);
        if (t.size() != a.size()) throw InputError(file + ": medium " + layer.name + " has sigma_t and albedo of different lengths");
        const double scale = named(medium, "scale") ? number_attribute(named(medium, "scale"), "value", file + ": scale") : 1.0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            layer.sigma_s_per_mm.push_back(a[i] * t[i] * scale);
            layer.sigma_a_per_mm.push_back(t[i] * scale - layer.sigma_s_per_mm.back());
        }
        const auto phase = medium.child("phase");
        const std::string type = phase ? phase.attribute("type").as_string() : "isotropic";
        if (type == "isotropic") {
            layer.phase = {RendererPhase::Kind::isotropic, 0.0, {}};
        } else if (type == "hg") {
            layer.phase.g = number_attribute(named(phase, "g"), "value", file + ": " + layer.name + " g");
        } else if (type == "tabphase") {
            layer.phase.kind = RendererPhase::Kind::tabulated;
            for (const auto field : split_fields(named(phase, "values").attribute("value").as_string())) {
                const auto v = parse_double(field);
                if (!v) throw InputError(file + ": " + layer.name + " tabphase value '" + std::string(field) + "' is not a number");
                layer.phase.values.push_back(*v);
            }
        } else {
            throw InputError(file + ": medium " + layer.name + " has phase '" + type + "' (allowed: hg, isotropic, tabphase)");
        }
        by_id[layer.name] = std::move(layer);
    }
    struct Face {
        double z;
        std::string interior, exterior, bsdf;
        double int_ior = 1.0, ext_ior = 1.0;
    };
    std::vector<Face> faces;
    for (const auto shape : scene.children("shape")) {
        if (std::string(shape.attribute("type").as_string()) != "rectangle") continue;
        Face f{0.0, {}, {}, {}};
        const auto translate = named(shape, "to_world").child("translate");
        if (translate) f.z = number_attribute(translate, "z", file + ": translate z");
        for (const auto ref : shape.children("ref")) {
            (std::string(ref.attribute("name").as_string()) == "interior" ? f.interior : f.exterior) = ref.attribute("id").as_string();
        }
        const auto bsdf = shape.child("bsdf");
        f.bsdf = bsdf.attribute("type").as_string();
        if (f.bsdf == "dielectric") {
            f.int_ior = number_attribute(named(bsdf, "int_ior"), "value", file + ": int_ior");
            f.ext_ior = number_attribute(named(bsdf, "ext_ior"), "value", file + ": ext_ior");
        }
        faces.push_back(f);
    }
    std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.z > b.z; });
    if (faces.empty()) throw InputError(file + ": no interfaces (rectangle shapes)");
    media.above_refractive_index = faces.front().ext_ior;
    double above = media.above_refractive_index;
    for (std::size_t k = 0; k < faces.size(); ++k) {
        const auto& f = faces[k];
        const double below_index = f.bsdf == "dielectric" ? f.int_ior : above;
        if (f.interior.empty()) {
            media.bottom_reflector = f.bsdf == "diffuse";
            media.below_refractive_index = below_index;
            break;
        }
        if (!by_id.contains(f.interior)) throw InputError(file + ": a rectangle names an unknown medium '" + f.interior + "'");
        if (k + 1 == faces.size()) throw InputError(file + ": medium '" + f.interior + "' has no interface below it");
        auto layer = by_id.at(f.interior);
        layer.thickness_mm = f.z - faces[k + 1].z;
        layer.refractive_index = below_index;
        above = below_index;
        media.layers.push_back(std::move(layer));
    }
    return media;
}

}  // namespace skinspec
