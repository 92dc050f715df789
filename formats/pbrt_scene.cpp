#include "formats/pbrt_scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// The radius of the interface disks (mm): 1000 times the skin's thickness, far beyond its diffusion length. Disks, not
// triangles: pbrt-v4's single-precision triangle test rejects hits closer than an offset that grows with the vertices'
// distance, so rays scattered within microns of a 2000 mm triangle crossed it unseen (R 1-6 % low; a disk's plane test
// is exact: epidermis alone 0.677 against the triangles' 0.618, measured with pbrt-v4, issue 37).
constexpr double interface_radius_mm = 1000.0;
// pbrt's volpath ends paths by Russian roulette; a depth limit only cuts paths short. 1000 biased R at 700 nm by
// -0.0008 (skin's albedo there is ~0.999, so 1000 events still carry 0.37 of the weight); 10^5 events carry below
// e^-100 of it.
constexpr int max_path_depth = 100'000;

std::string number_list(const std::vector<double>& values) {
    std::string out;
    for (const double v : values) {
        if (!out.empty()) out += ' ';
        out += format_number(v);
    }
    return out;
}

std::string spectrum_parameter(const RendererMedia& media, const std::filesystem::path& scene, const RendererLayer& layer, const std::string& quantity,
                               const std::vector<double>& values) {
    if (media.rgb) return fmt::format("\"rgb {}\" [ {} ]", quantity, number_list(values));
    return fmt::format("\"spectrum {}\" \"{}\"", quantity, spectrum_file_reference(scene, layer.name, quantity));
}

// A horizontal interface at height z, its normal up (+z, as the medium interface's exterior).
std::string interface_disk(double z_mm) {
    return fmt::format("    Shape \"disk\" \"float height\" [ {} ] \"float radius\" [ {} ]\n", format_number(z_mm), format_number(interface_radius_mm));
}

std::string interface_material(double eta) {
    return eta == 1.0 ? std::string("    Material \"interface\"\n") : fmt::format("    Material \"dielectric\" \"float eta\" [ {} ]\n", format_number(eta));
}

// --- reading -----------------------------------------------------------------------------------------------

struct Token {
    enum class Kind { word, string, number, open, close } kind;
    std::string text;
    int line;
};

std::vector<Token> tokenize(const std::string& text, const std::string& file) {
    std::vector<Token> tokens;
    int line = 1;
    for (std::size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (c == '\n') ++line;
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else if (c == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
        } else if (c == '[' || c == ']') {
            tokens.push_back({c == '[' ? Token::Kind::open : Token::Kind::close, std::string(1, c), line});
            ++i;
        } else if (c == '"') {
            const auto end = text.find('"', i + 1);
            if (end == std::string::npos) throw InputError(file + " line " + std::to_string(line) + ": unterminated string");
            tokens.push_back({Token::Kind::string, text.substr(i + 1, end - i - 1), line});
            i = end + 1;
        } else {
            std::size_t end = i;
            while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) && text[end] != '[' && text[end] != ']' && text[end] != '"') ++end;
            const auto word = text.substr(i, end - i);
            tokens.push_back({parse_double(word) ? Token::Kind::number : Token::Kind::word, word, line});
            i = end;
        }
    }
    return tokens;
}

struct Parameter {
    std::string type;
    std::vector<std::string> values;  // numbers as text, or strings
};

struct Directive {
    std::string name;
    std::vector<std::string> arguments;  // strings and numbers before the parameter list
    std::map<std::string, Parameter> parameters;
    int line = 0;
};

std::vector<Directive> parse_directives(const std::vector<Token>& tokens, const std::string& file) {
    std::vector<Directive> out;
    const auto fail = [&](const Token& t, const std::string& what) { throw InputError(file + " line " + std::to_string(t.line) + ": " + what); };
    for (std::size_t i = 0; i < tokens.size();) {
        if (tokens[i].kind != Token::Kind::word) fail(tokens[i], "expected a directive, got '" + tokens[i].text + "'");
        Directive d{tokens[i].text, {}, {}, tokens[i].line};
        ++i;
        // Positional arguments: strings without a space (a parameter's "type name" has one) and numbers.
        while (i < tokens.size() && (tokens[i].kind == Token::Kind::number || (tokens[i].kind == Token::Kind::string && tokens[i].text.find(' ') == std::string::npos))) {
            d.arguments.push_back(tokens[i++].text);
        }
        while (i < tokens.size() && tokens[i].kind == Token::Kind::string) {
            const auto declaration = tokens[i].text;
            const auto space = declaration.find(' ');
            ++i;
            Parameter p{declaration.substr(0, space), {}};
            if (i < tokens.size() && tokens[i].kind == Token::Kind::open) {
                ++i;
                while (i < tokens.size() && tokens[i].kind != Token::Kind::close) p.values.push_back(tokens[i++].text);
                if (i == tokens.size()) fail(tokens.back(), "unterminated [ in parameter '" + declaration + "'");
                ++i;
            } else if (i < tokens.size() && (tokens[i].kind == Token::Kind::number || tokens[i].kind == Token::Kind::string)) {
                p.values.push_back(tokens[i++].text);
            } else {
                fail(tokens[i - 1], "parameter '" + declaration + "' has no value");
            }
            d.parameters[std::string(trim(declaration.substr(space + 1)))] = std::move(p);
        }
        out.push_back(std::move(d));
    }
    return out;
}

double number_of(const Parameter& p, const std::string& what) {
    if (p.values.size() != 1) throw InputError(what + ": expected one number");
    const auto v = parse_double(p.values[0]);
    if (!v) throw InputError(what + ": '" + p.values[0] + "' is not a number");
    return *v;
}

std::vector<double> numbers_of(const Parameter& p, const std::string& what) {
    std::vector<double> out;
    for (const auto& t : p.values) {
        const auto v = parse_double(t);
        if (!v) throw InputError(what + ": '" + t + "' is not a number");
        out.push_back(*v);
    }
    return out;
}

}  // namespace

std::vector<std::filesystem::path> pbrt_scene_files(const RendererMedia& media, const std::filesystem::path& scene) {
    return scene_files(media, scene, {"sigma_a", "sigma_s"});
}

void write_pbrt_scene(const RendererMedia& media, const std::filesystem::path& scene, std::string_view note) {
    for (const auto& l : media.layers) {
        if (l.phase.kind == RendererPhase::Kind::tabulated) {
            throw InputError("layer '" + l.name + "' has a measured (tabulated) phase function; pbrt-v4 media take Henyey-Greenstein only "
                             "(use --phase hg, HG with the profile's mean cosine, or export mitsuba, whose tabphase takes the table)");
        }
    }
    if (!media.rgb) {
        std::filesystem::create_directories(spectra_folder(scene));
        for (const auto& l : media.layers) {
            write_spd_file(spectrum_file_path(scene, l.name, "sigma_a"), media.wavelengths_nm, l.sigma_a_per_mm,
                           fmt::format("skinspec {}: {} layer {} absorption coefficient sigma_a [1/mm]", version, media.material, l.name));
            write_spd_file(spectrum_file_path(scene, l.name, "sigma_s"), media.wavelengths_nm, l.sigma_s_per_mm,
                           fmt::format("skinspec {}: {} layer {} scattering coefficient sigma_s [1/mm]", version, media.material, l.name));
        }
    }
    double depth_mm = 0.0;
    for (const auto& l : media.layers) depth_mm += l.thickness_mm;
    std::string text = fmt::format("# skinspec {}: {} as pbrt-v4 media under uniform D65 light, seen straight down. Scene units mm; sigma_a, sigma_s in 1/mm.\n",
                                   version, media.material);
    text += media.rgb ? fmt::format("# RGB media: the coefficients at {} nm taken as R, G, B.\n", number_list(media.wavelengths_nm))
                      : fmt::format("# Spectral media: {} wavelengths, {}-{} nm, in {}/.\n", media.wavelengths_nm.size(), format_number(media.wavelengths_nm.front()),
                                    format_number(media.wavelengths_nm.back()), spectra_folder(scene).filename().string());
    text += fmt::format("# Phase functions at {:.6g} nm. Layers top to bottom from z = 0 (total {:.6g} mm); index above {:.6g}.\n",
                        media.phase_wavelength_nm, depth_mm, media.above_refractive_index);
    if (!note.empty()) text += fmt::format("# {}\n", note);
    // A light a path tracer reaches through the specular interfaces (a distant light rendered black, issue 65): a uniform
    // environment, which pbrt-v4 scales to 1 nit; the camera straight down over scene_view_mm of the slab.
    text += fmt::format("LookAt 0 0 50  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [ {0} {1} {0} {1} ]\n", format_number(-scene_view_mm / 2),
                        format_number(scene_view_mm / 2));
    text += fmt::format("Sampler \"zsobol\" \"integer pixelsamples\" [ {} ]\nIntegrator \"volpath\" \"integer maxdepth\" [ {} ]\n", scene_samples_per_pixel,
                        max_path_depth);
    text += fmt::format("Film \"rgb\" \"string filename\" [ \"{0}.exr\" ] \"integer xresolution\" [ {1} ] \"integer yresolution\" [ {1} ]\n",
                        scene.stem().string(), scene_pixels);
    text += "WorldBegin\nLightSource \"infinite\" \"spectrum L\" \"stdillum-D65\"\n\n";
    for (const auto& l : media.layers) {
        text += fmt::format("# {}: {:.6g} mm, index {:.6g}, phase HG g {:.6g}\n", l.name, l.thickness_mm, l.refractive_index, l.phase.g);
        text += fmt::format("MakeNamedMedium \"{}\" \"string type\" \"homogeneous\"\n    {}\n    {}\n    \"float g\" [ {} ] \"float scale\" [ 1 ]\n", l.name,
                            spectrum_parameter(media, scene, l, "sigma_a", l.sigma_a_per_mm), spectrum_parameter(media, scene, l, "sigma_s", l.sigma_s_per_mm),
                            format_number(l.phase.kind == RendererPhase::Kind::isotropic ? 0.0 : l.phase.g));
    }
    double z = 0.0, above = media.above_refractive_index;
    std::string outside;
    for (const auto& l : media.layers) {
        text += fmt::format("\nAttributeBegin  # interface at z = {:.6g} mm: {} below, {} above\n", z, l.name, outside.empty() ? "outside" : outside);
        text += fmt::format("    MediumInterface \"{}\" \"{}\"\n", l.name, outside);
        text += interface_material(l.refractive_index / above);
        text += interface_disk(z);
        text += "AttributeEnd\n";
        z -= l.thickness_mm;
        above = l.refractive_index;
        outside = l.name;
    }
    text += fmt::format("\nAttributeBegin  # bottom at z = {:.6g} mm\n    MediumInterface \"\" \"{}\"\n", z, outside);
    text += media.bottom_reflector ? std::string("    Material \"diffuse\" \"rgb reflectance\" [ 1 1 1 ]\n") : interface_material(media.below_refractive_index / above);
    text += interface_disk(z) + "AttributeEnd\n";
    write_text_file(scene, text, true);
}

RendererMedia read_pbrt_scene(const std::filesystem::path& scene, double above_refractive_index) {
    std::ifstream in(scene);
    if (!in) throw InputError("pbrt scene " + scene.string() + " cannot be read");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const auto file = scene.string();
    const auto directives = parse_directives(tokenize(buffer.str(), file), file);

    RendererMedia media;
    media.above_refractive_index = above_refractive_index;
    std::map<std::string, RendererLayer> media_by_name;
    struct Interface {
        double z;
        std::string interior, exterior;
        std::optional<double> eta;  // none: diffuse reflector
    };
    std::vector<Interface> interfaces;
    std::string interior, exterior, material = "diffuse";
    std::optional<double> eta;
    const auto spectrum = [&](const Directive& d, const std::string& quantity) {
        const auto it = d.parameters.find(quantity);
        const auto where = file + " line " + std::to_string(d.line) + ": medium " + d.arguments.at(0) + " " + quantity;
        if (it == d.parameters.end()) throw InputError(where + " is missing");
        if (it->second.type == "rgb") {
            media.rgb = true;
            return numbers_of(it->second, where);
        }
        if (it->second.type != "spectrum" || it->second.values.size() != 1) throw InputError(where + ": expected a spectrum file or rgb");
        auto [nm, values] = read_spd_file(scene.parent_path() / it->second.values[0]);
        media.wavelengths_nm = nm;
        return values;
    };
    for (const auto& d : directives) {
        if (d.name == "MakeNamedMedium") {
            if (d.arguments.size() != 1) throw InputError(file + " line " + std::to_string(d.line) + ": MakeNamedMedium takes one name");
            RendererLayer layer;
            layer.name = d.arguments[0];
            layer.sigma_a_per_mm = spectrum(d, "sigma_a");
            layer.sigma_s_per_mm = spectrum(d, "sigma_s");
            const double scale = d.parameters.contains("scale") ? number_of(d.parameters.at("scale"), file + ": scale") : 1.0;
            for (auto& v : layer.sigma_a_per_mm) v *= scale;
            for (auto& v : layer.sigma_s_per_mm) v *= scale;
            layer.phase.g = d.parameters.contains("g") ? number_of(d.parameters.at("g"), file + ": g") : 0.0;
            media_by_name[layer.name] = layer;
        } else if (d.name == "AttributeBegin") {
            interior.clear();
            exterior.clear();
            material = "diffuse";
            eta.reset();
        } else if (d.name == "MediumInterface") {
            interior = d.arguments.size() > 0 ? d.arguments[0] : "";
            exterior = d.arguments.size() > 1 ? d.arguments[1] : interior;
        } else if (d.name == "Material") {
            material = d.arguments.empty() ? "" : d.arguments[0];
            eta = material == "interface" ? std::optional<double>(1.0) : std::nullopt;
            if (material == "dielectric") eta = d.parameters.contains("eta") ? number_of(d.parameters.at("eta"), file + ": eta") : 1.5;
        } else if (d.name == "Shape" && !d.arguments.empty() && d.arguments[0] == "disk") {
            const double height = d.parameters.contains("height") ? number_of(d.parameters.at("height"), file + ": height") : 0.0;
            interfaces.push_back({height, interior, exterior, material == "diffuse" ? std::nullopt : eta});
        } else if (d.name == "Shape" && !d.arguments.empty() && d.arguments[0] == "trianglemesh") {
            if (!d.parameters.contains("P")) throw InputError(file + " line " + std::to_string(d.line) + ": a trianglemesh without \"point3 P\"");
            const auto p = numbers_of(d.parameters.at("P"), file + ": P");
            if (p.empty() || p.size() % 3 != 0) throw InputError(file + " line " + std::to_string(d.line) + ": P is not a list of points");
            for (std::size_t i = 2; i < p.size(); i += 3) {
                if (p[i] != p[2]) throw InputError(file + " line " + std::to_string(d.line) + ": an interface that is not horizontal");
            }
            interfaces.push_back({p[2], interior, exterior, material == "diffuse" ? std::nullopt : eta});
        }
    }
    std::sort(interfaces.begin(), interfaces.end(), [](const Interface& a, const Interface& b) { return a.z > b.z; });
    double above = above_refractive_index;
    for (std::size_t k = 0; k < interfaces.size(); ++k) {
        const auto& face = interfaces[k];
        if (face.interior.empty()) {  // the bottom
            media.bottom_reflector = !face.eta;
            if (face.eta) media.below_refractive_index = *face.eta * above;
            break;
        }
        if (!media_by_name.contains(face.interior)) throw InputError(file + ": interface below '" + face.exterior + "' names an unknown medium '" + face.interior + "'");
        if (!face.eta) throw InputError(file + ": the interface above medium '" + face.interior + "' is not a dielectric");
        auto layer = media_by_name.at(face.interior);
        if (k + 1 == interfaces.size()) throw InputError(file + ": medium '" + face.interior + "' has no interface below it");
        layer.thickness_mm = face.z - interfaces[k + 1].z;
        layer.refractive_index = *face.eta * above;
        above = layer.refractive_index;
        media.layers.push_back(std::move(layer));
    }
    return media;
}

}  // namespace skinspec
