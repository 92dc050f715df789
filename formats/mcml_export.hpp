#pragma once
// A material's volumetric description as MCML 1.2 input (`skinspec export mcml`, docs/PROFILES.md): one run per
// wavelength, the layers of rte_stack_from (for the skin presets the description derived from the BioSpec model), a
// radial grid for skin, so that MCML, CUDAMCML or MCX users can run the skin the exact profiles describe.
//
// MCML cannot hold all of it: its layers scatter by Henyey-Greenstein only and its bottom is a Fresnel interface, not
// a Lambertian reflector. The export substitutes, and says what: a measured (tabulated), Rayleigh or two-term phase
// function becomes HG with the same mean cosine (the same transport mean free path; the shape near the source is
// what changes), and the bottom reflector is left out (light reaching the bottom leaves through it, into a medium of
// the last layer's index). It also measures what the substitutions change: the diffuse reflectance of both stacks by
// adding-doubling (an independent solution of each), so a comparison of MCML's R(r) with skinspec's knows what to
// compare against: the walk on the exported file (`skinspec mcml FILE.mci`), not the default profile.
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mcml_files.hpp"
#include "materials/layer_stack.hpp"

namespace skinspec {

struct McmlExportRequest {
    std::vector<double> wavelengths_nm{450.0, 550.0, 650.0};
    std::uint64_t photons = 10'000'000;
    double ring_mm = 0.01;    // MCML's dr
    double reach_mm = 5.0;    // nr = reach / ring
    double depth_bin_mm = 0.01;  // MCML's dz, over the stack's depth (at most 10000 bins)
    int angle_bins = 30;
    std::string output_stem = "skin";  // each run writes STEM_NNNnm.mco
};

struct McmlExport {
    std::vector<McmlRun> runs;
    std::vector<std::string> substitutions;  // what MCML could not hold, once per layer and kind
    // Per run: adding-doubling's diffuse reflectance of the exported stack and of the material's own description.
    std::vector<double> exported_reflectance, own_reflectance;
};

// InputError for a request outside its ranges (wavelengths 250-2500 nm, photons [100, 1e15], ring (0, reach], reach
// (0, 1000] mm, more than 100000 rings) or a layer without volumetric scattering.
McmlExport mcml_export(const LayerStack& stack, const McmlExportRequest& request);

// The comment lines the .mci opens with (and the command prints): the material and wavelengths, what was substituted,
// and adding-doubling's diffuse R of the file's stack against the material's own description per wavelength.
std::vector<std::string> mcml_export_comments(const McmlExport& exported, const std::string& material, const std::vector<double>& wavelengths_nm);

}  // namespace skinspec
