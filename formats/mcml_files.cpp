#include "formats/mcml_files.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// The .mci's non-comment lines, each split into fields, with their line numbers.
class MciLines {
public:
    explicit MciLines(const std::filesystem::path& file) : name_(file.string()) {
        auto in = open_input_file(file, ".mci file");
        std::string line;
        std::size_t number = 0;
        while (std::getline(in, line)) {
            ++number;
            const auto hash = line.find('#');
            const auto text = trim(std::string_view(line).substr(0, hash));
            if (text.empty()) continue;
            std::vector<std::string> fields;
            for (const auto f : split_fields(text)) fields.emplace_back(f);
            lines_.push_back({number, std::move(fields)});
        }
    }

    // The next line with exactly `count` fields named by `what`.
    const std::vector<std::string>& next(std::size_t count, const std::string& what) {
        if (index_ >= lines_.size()) throw InputError(name_ + ": ends early: expected " + what);
        const auto& [number, fields] = lines_[index_++];
        line_ = number;
        if (fields.size() < count) {
            throw InputError(where() + "expected " + what + " (" + std::to_string(count) + " field(s)), found " + std::to_string(fields.size()));
        }
        return fields;
    }

    double number(const std::string& field, const std::string& what, double lo, double hi, bool lo_open) {
        const auto v = parse_double(field);
        const bool ok = v && std::isfinite(*v) && (lo_open ? *v > lo : *v >= lo) && *v <= hi;
        if (!ok) {
            throw InputError(where() + "field '" + what + "' = " + field + " is outside " + (lo_open ? "(" : "[") + format_number(lo) +
                             ", " + (std::isinf(hi) ? std::string("inf") : format_number(hi)) + "]");
        }
        return *v;
    }

    std::uint64_t whole(const std::string& field, const std::string& what, double lo, double hi) {
        const double v = number(field, what, lo, hi, false);
        if (v != std::floor(v)) throw InputError(where() + "field '" + what + "' = " + field + " is not a whole number");
        return static_cast<std::uint64_t>(v);
    }

    std::string where() const { return name_ + ":" + std::to_string(line_) + ": "; }
    bool done() const { return index_ >= lines_.size(); }

private:
    std::string name_;
    std::vector<std::pair<std::size_t, std::vector<std::string>>> lines_;
    std::size_t index_ = 0;
    std::size_t line_ = 0;
};

constexpr double inf = std::numeric_limits<double>::infinity();

std::string array_lines(const std::vector<Estimate>& v) {
    std::string out;
    for (const auto& e : v) out += fmt::format("{:12.4E}\n", e.value);
    return out;
}

std::string grid_lines(const std::vector<Estimate>& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i) {
        out += fmt::format("{:12.4E} ", v[i].value);
        if ((i + 1) % 5 == 0) out += '\n';
    }
    return out + '\n';
}

}  // namespace

std::vector<McmlRun> read_mci(const std::filesystem::path& file) {
    MciLines lines(file);
    const auto& version = lines.next(1, "the file version (1.0)");
    lines.number(version[0], "file version", 1.0, 1.0, false);
    const auto runs = lines.whole(lines.next(1, "the number of runs")[0], "number of runs", 1, 1e6);
    std::vector<McmlRun> out;
    for (std::uint64_t r = 0; r < runs; ++r) {
        McmlRun run;
        const auto& name = lines.next(2, "output file name and format (A or B)");
        run.output_file = name[0];
        if (name[1] != "A" && name[1] != "a" && name[1] != "B" && name[1] != "b") {
            throw InputError(lines.where() + "field 'format' = " + name[1] + " is not allowed (allowed: A, B)");
        }
        run.output_format = static_cast<char>(std::toupper(name[1][0]));
        run.photons = lines.whole(lines.next(1, "the number of photons")[0], "No. of photons", 1, 1e15);
        const auto& spacing = lines.next(2, "dz dr [cm]");
        run.grid.dz_cm = lines.number(spacing[0], "dz [cm]", 0.0, inf, true);
        run.grid.dr_cm = lines.number(spacing[1], "dr [cm]", 0.0, inf, true);
        const auto& bins = lines.next(3, "No. of dz, dr, da");
        run.grid.nz = static_cast<int>(lines.whole(bins[0], "No. of dz", 1, 100000));
        run.grid.nr = static_cast<int>(lines.whole(bins[1], "No. of dr", 1, 100000));
        run.grid.na = static_cast<int>(lines.whole(bins[2], "No. of da", 1, 100000));
        const auto layers = lines.whole(lines.next(1, "the number of layers")[0], "Number of layers", 1, 1000);
        run.stack.above_refractive_index = lines.number(lines.next(1, "n for medium above")[0], "n above", 0.0, inf, true);
        for (std::uint64_t k = 0; k < layers; ++k) {
            const auto& f = lines.next(5, "layer " + std::to_string(k + 1) + ": n mua mus g d");
            const std::string l = "layer " + std::to_string(k + 1) + " ";
            RteLayer layer;
            layer.refractive_index = lines.number(f[0], l + "n", 0.0, inf, true);
            layer.mu_a_per_cm = lines.number(f[1], l + "mua [1/cm]", 0.0, inf, false);
            layer.mu_s_per_cm = lines.number(f[2], l + "mus [1/cm]", 0.0, inf, false);
            layer.phase = PhaseFunction::henyey_greenstein(lines.number(f[3], l + "g", -1.0, 1.0, false));
            layer.thickness_cm = lines.number(f[4], l + "d [cm]", 0.0, inf, true);
            run.stack.layers.push_back(layer);
        }
        run.stack.below_refractive_index = lines.number(lines.next(1, "n for medium below")[0], "n below", 0.0, inf, true);
        out.push_back(std::move(run));
    }
    if (!lines.done()) throw InputError(lines.where() + "unexpected lines after the last run");
    return out;
}

std::string run_parameters_text(const McmlRun& run) {
    const auto& g = run.grid;
    std::string out = fmt::format("{} \tA\t\t# output file name, ASCII.\n", run.output_file);
    out += fmt::format("{} \t\t\t# No. of photons\n", run.photons);
    out += fmt::format("{:G}\t{:G}\t\t# dz, dr [cm]\n", g.dz_cm, g.dr_cm);
    out += fmt::format("{}\t{}\t{}\t# No. of dz, dr, da.\n\n", g.nz, g.nr, g.na);
    out += fmt::format("{}\t\t\t\t\t# Number of layers\n", run.stack.layers.size());
    out += "#n\tmua\tmus\tg\td\t# One line for each layer\n";
    out += fmt::format("{:G}\t\t\t\t\t# n for medium above\n", run.stack.above_refractive_index);
    for (std::size_t k = 0; k < run.stack.layers.size(); ++k) {
        const auto& l = run.stack.layers[k];
        out += fmt::format("{:G}\t{:G}\t{:G}\t{:G}\t{:G}\t# layer {}\n", l.refractive_index, l.mu_a_per_cm, l.mu_s_per_cm, l.phase.g,
                           l.thickness_cm, k + 1);
    }
    out += fmt::format("{:G}\t\t\t\t\t# n for medium below\n", run.stack.below_refractive_index);
    return out;
}

std::string mci_text(const std::vector<McmlRun>& runs, const std::vector<std::string>& comments) {
    std::string out = "####\n";
    for (const auto& c : comments) out += "# " + c + "\n";
    out += "####\n1.0\t\t\t\t\t# file version\n";
    out += fmt::format("{}\t\t\t\t\t# number of runs\n", runs.size());
    for (std::size_t i = 0; i < runs.size(); ++i) out += fmt::format("\n#### SPECIFY DATA FOR RUN {}\n#InParm\n", i + 1) + run_parameters_text(runs[i]);
    return out;
}

std::string mco_text(const McmlRun& run, const RteResult& r, const std::string& time_report, bool grids) {
    std::string out = "A1 \t# Version number of the file format.\n\n"
                      "####\n# Data categories include: \n# InParm, RAT, \n# A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, \n"
                      "# A_rz, Rd_ra, Tt_ra \n####\n\n";
    out += "# " + time_report + "\n\n";
    out += "InParm \t\t\t# Input parameters. cm is used.\n" + run_parameters_text(run) + "\n";
    out += "RAT #Reflectance, absorption, transmission. \n";
    out += fmt::format("{:<14.6G} \t#Specular reflectance [-]\n", r.specular_reflectance.value);
    out += fmt::format("{:<14.6G} \t#Diffuse reflectance [-]\n", r.diffuse_reflectance.value);
    out += fmt::format("{:<14.6G} \t#Absorbed fraction [-]\n", r.absorbed.value);
    out += fmt::format("{:<14.6G} \t#Transmittance [-]\n\n", r.transmittance.value);
    out += "A_l #Absorption as a function of layer. [-]\n";
    for (const auto& a : r.absorption_layers) out += fmt::format("{:12.4G}\n", a.value);
    if (!grids) return out + "\n# A_z, Rd_r, Rd_a, Tt_r, Tt_a and the 2-D grids: not computed by this solver (the volumetric walk computes them)\n";
    out += "\nA_z #A[0], [1],..A[nz-1]. [1/cm]\n" + array_lines(r.absorption_z);
    out += "\nRd_r #Rd[0], [1],..Rd[nr-1]. [1/cm2]\n" + array_lines(r.reflectance_r);
    out += "\nRd_a #Rd[0], [1],..Rd[na-1]. [sr-1]\n" + array_lines(r.reflectance_a);
    out += "\nTt_r #Tt[0], [1],..Tt[nr-1]. [1/cm2]\n" + array_lines(r.transmittance_r);
    out += "\nTt_a #Tt[0], [1],..Tt[na-1]. [sr-1]\n" + array_lines(r.transmittance_a);
    out += "\n# A[r][z]. [1/cm3]\n# A[0][0], [0][1],..[0][nz-1]\n# A[1][0], [1][1],..[1][nz-1]\n# ...\n"
           "# A[nr-1][0], [nr-1][1],..[nr-1][nz-1]\nA_rz\n" + grid_lines(r.absorption_rz);
    out += "\n# Rd[r][angle]. [1/(cm2sr)].\n# Rd[0][0], [0][1],..[0][na-1]\n# Rd[1][0], [1][1],..[1][na-1]\n# ...\n"
           "# Rd[nr-1][0], [nr-1][1],..[nr-1][na-1]\nRd_ra\n" + grid_lines(r.reflectance_ra);
    out += "\n# Tt[r][angle]. [1/(cm2sr)].\n# Tt[0][0], [0][1],..[0][na-1]\n# Tt[1][0], [1][1],..[1][na-1]\n# ...\n"
           "# Tt[nr-1][0], [nr-1][1],..[nr-1][na-1]\nTt_ra\n" + grid_lines(r.transmittance_ra);
    return out;
}

RteRequest mcml_request(const McmlRun& run, std::uint64_t seed, BoundaryMode boundaries) {
    RteRequest request;
    request.stack = run.stack;
    request.photons = run.photons;
    request.seed = seed;
    request.boundaries = boundaries;
    request.grid = run.grid;
    return request;
}

namespace {

nlohmann::ordered_json estimates(const std::vector<Estimate>& v, const char* key) {
    std::vector<double> value, stderr;
    for (const auto& e : v) {
        value.push_back(e.value);
        stderr.push_back(e.stderr);
    }
    return nlohmann::ordered_json{{key, value}, {std::string(key) + "_stderr", stderr}};
}

}  // namespace

nlohmann::ordered_json mcml_run_json(const McmlRun& run, const RteResult& r, double seconds) {
    using Json = nlohmann::ordered_json;
    Json j{{"model", "rte"},
           {"input", Json{{"output_file", run.output_file}, {"photons", run.photons}, {"dz_cm", run.grid.dz_cm}, {"dr_cm", run.grid.dr_cm},
                          {"nz", run.grid.nz}, {"nr", run.grid.nr}, {"na", run.grid.na}}},
           {"partial", r.partial},
           {"photons", r.photons},
           {"truncated_photons", r.truncated_photons},
           {"seconds", seconds},
           {"R", r.specular_reflectance.value + r.diffuse_reflectance.value},
           {"R_stderr", r.diffuse_reflectance.stderr},
           {"R_specular", r.specular_reflectance.value},
           {"R_specular_stderr", r.specular_reflectance.stderr},
           {"R_diffuse", r.diffuse_reflectance.value},
           {"R_diffuse_stderr", r.diffuse_reflectance.stderr},
           {"T", r.transmittance.value},
           {"T_stderr", r.transmittance.stderr},
           {"A", r.absorbed.value},
           {"A_stderr", r.absorbed.stderr}};
    j.update(estimates(r.absorption_layers, "A_layers"));
    j.update(estimates(r.absorption_z, "A_z_per_cm"));
    j.update(estimates(r.reflectance_r, "R_r_per_cm2"));
    j.update(estimates(r.transmittance_r, "T_r_per_cm2"));
    j.update(estimates(r.reflectance_a, "R_a_per_sr"));
    j.update(estimates(r.transmittance_a, "T_a_per_sr"));
    j.update(estimates(r.absorption_rz, "A_rz_per_cm3"));
    j.update(estimates(r.reflectance_ra, "R_ra_per_cm2_sr"));
    j.update(estimates(r.transmittance_ra, "T_ra_per_cm2_sr"));
    return j;
}

}  // namespace skinspec
