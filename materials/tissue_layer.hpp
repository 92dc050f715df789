#pragma once
// A tissue layer: geometry, refractive index, absorbers, and the scattering descriptions that the solvers
// use (per-crossing BioSpec scattering, and optionally volumetric mu_s with a phase function and reduced
// scattering mu_s' for diffusion), so one description feeds every solver.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "materials/model_options.hpp"

namespace skinspec {

// What happens to a ray's direction each time it crosses the layer (BioSpec walk).
enum class CrossingScattering {
    measured_stratum_corneum,  // Bruls & van der Leun SC profile, randomized table look-up
    measured_epidermis,        // Bruls & van der Leun epidermis profile
    rayleigh_cosine,           // Rayleigh by collagen fibres with probability 1 - exp(-beta d / |cos|), else cosine
    cosine,                    // cosine-distributed about the normal
    henyey_greenstein,         // HG with asymmetry hg_g about the current direction
};
std::string_view to_string(CrossingScattering kind);
// The dermal kinds (a cosine turn, with or without Rayleigh), as against the thin layers' single deflection.
constexpr bool is_dermal(CrossingScattering kind) { return kind == CrossingScattering::rayleigh_cosine || kind == CrossingScattering::cosine; }
CrossingScattering parse_crossing_scattering(std::string_view text, std::string_view what);

// Volumetric phase functions: HG (volumetric_g), isotropic, Rayleigh, or a measured profile (Bruls & van der Leun
// 1984) used as a tabulated phase function, whose g is the profile's mean cosine at the wavelength.
enum class PhaseFunctionKind { henyey_greenstein, isotropic, rayleigh, measured_stratum_corneum, measured_epidermis };
bool is_measured(PhaseFunctionKind kind);
std::string_view to_string(PhaseFunctionKind kind);
PhaseFunctionKind parse_phase_function(std::string_view text, std::string_view what);

// Where the volumetric mu_s comes from: its own power law, or the layer's reduced scattering (table or power law)
// as mu_s = mu_s' / (1 - g), so that every solver sees the same mu_s' (one skin in every mode).
enum class VolumetricSource { power_law, from_reduced_scattering };
std::string_view to_string(VolumetricSource source);
VolumetricSource parse_volumetric_source(std::string_view text, std::string_view what);

// Volumetric scattering for radiative-transfer walks: mu_s(lambda) = mu_s(500 nm) * (lambda / 500 nm)^-power, or
// from the reduced scattering (VolumetricSource).
struct VolumetricScattering {
    double mu_s_per_cm_at_500nm = 0.0;
    double power = 0.0;
    PhaseFunctionKind phase = PhaseFunctionKind::henyey_greenstein;
    double g = 0.0;  // HG only (a measured phase has its own mean cosine)
    VolumetricSource source = VolumetricSource::power_law;
    bool operator==(const VolumetricScattering&) const = default;
};

// Reduced scattering for diffusion: either a measured table (data/tissue/<table>.csv, column
// mu_s_reduced_per_mm) or the power law mu_s'(lambda) = a * (lambda / 500 nm)^-b.
struct ReducedScattering {
    std::string table;  // "salomatina_epidermis", "salomatina_dermis", "salomatina_hypodermis", or empty
    double per_cm_at_500nm = 0.0;
    double power = 0.0;
    bool operator==(const ReducedScattering&) const = default;
};

// Names of the measured reduced-scattering tables in data/tissue.
const std::vector<std::string_view>& reduced_scattering_tables();

struct TissueLayer {
    std::string name;
    double thickness_cm = 0.0;
    double refractive_index = 1.0;

    // Absorbers. The layer is a mixture: melanosomes (volume fraction), whole blood (volume fraction) and a
    // background of the remaining volume holding carotene and the baseline tissue absorption.
    double melanosome_fraction = 0.0;
    double eumelanin_mg_per_ml = 80.0;     // inside melanosomes
    double pheomelanin_mg_per_ml = 12.0;   // inside melanosomes
    double blood_fraction = 0.0;
    double oxygen_saturation = 0.75;
    double hemoglobin_g_per_l = 150.0;     // in whole blood
    double bilirubin_g_per_l = 0.05;       // in whole blood
    double carotene_g_per_l = 0.0;         // in the background
    double vessel_radius_um = 0.0;         // mean radius of the vessels holding the blood; 0: blood spread evenly
    double melanin_cluster_radius_um = 0.0;  // radius of the spheres holding the melanosomes (sieve effect); 0: spread evenly
    double water_fraction = 0.0;           // volume fraction of water in the layer (blood's water included)
    double lipid_fraction = 0.0;           // volume fraction of lipid in the layer

    CrossingScattering crossing = CrossingScattering::cosine;
    double hg_g = 0.0;                         // for henyey_greenstein
    double collagen_fibre_fraction = 0.21;     // for rayleigh_cosine
    double collagen_fibre_radius_nm = 25.0;
    double collagen_fibre_index = 1.5;
    // Dermal scattering by structures beyond the Rayleigh regime (fibre bundles, cells; "Mie"), as a reduced
    // coefficient a (lambda / 500 nm)^-b added to the turn test of rayleigh_cosine crossings; 0: BioSpec (Rayleigh only).
    double mie_reduced_scattering_per_cm_at_500nm = 0.0;
    double mie_reduced_scattering_power = 0.678;  // the measured dermis' tail, 500-1610 nm (data/tissue/salomatina_dermis.csv)
    std::optional<VolumetricScattering> volumetric;
    std::optional<ReducedScattering> reduced;

    bool operator==(const TissueLayer&) const = default;
};

// Absorption coefficient [1/cm] at a wavelength (Krishnaswamy & Baranoski 2004; docs/MATERIALS.md, "Layers and stacks"):
//   mu_a = v_m (mu_eu + mu_ph) + v_b (S mu_HbO2 + (1 - S) mu_Hb + mu_bili) + (1 - v_m - v_b) (mu_car + mu_base)
//          + v_w mu_water + v_l mu_lipid,
// the last two over the whole layer (Jacques 2013, Phys Med Biol 58:R37, Eq. 12; the haemoglobin tables hold no water).
// Terms with zero weight are not evaluated, so a chromophore's table range only matters where it is present.
// With a vessel radius R_v > 0 the blood term is packaged (Svaasand et al. 1995, Lasers Med Sci 10:55; Verkruysse
// et al. 1997, Phys Med Biol 42:51, Eq. 6; van Veen et al. 2002, Opt Lett 27:246): v_b C mu_blood with
// C = (1 - exp(-2 mu_blood R_v)) / (2 mu_blood R_v). With a melanin cluster radius r > 0 the melanosome term is
// packaged the same way in spheres (the sieve effect): v_m C_s mu_mel, C_s = sphere_packaging_factor.
double absorption_per_cm(const TissueLayer& layer, double wavelength_nm, const ModelOptions& model);

// Rayleigh coefficient of the collagen fibres [1/cm] (Krishnaswamy & Baranoski 2004; docs/BIOSPEC.md "One ray", step 2):
//   beta = 8 pi^3 (eta^2 - 1)^2 / (3 N lambda^4), eta = n_fibre / n_layer, N = f / (4/3 pi r^3),
// with lambda and r in cm.
double rayleigh_coefficient_per_cm(const TissueLayer& layer, double wavelength_nm);

// The layer's Mie reduced scattering [1/cm], a (lambda / 500 nm)^-b (Jacques 2013, Phys Med Biol 58:R37, Eq. 1). It
// enters the turn test of a rayleigh_cosine crossing beside the Rayleigh coefficient, and a turn it causes takes the
// Rayleigh turn's direction: by the similarity relation (ibid., Eq. 2) a forward-peaked phase of coefficient mu_s acts
// as mu_s' = mu_s (1 - g) with a phase of mean cosine 0, which the Rayleigh phase is.
double mie_reduced_scattering_per_cm(const TissueLayer& layer, double wavelength_nm);

// The packaging factor C above for whole-blood absorption mu_blood [1/cm] and vessel radius [um]; 1 at radius 0.
double vessel_packaging_factor(double mu_blood_per_cm, double vessel_radius_um);

// Sieve effect of absorbing spheres of radius r [um] and absorption mu [1/cm] in a transparent medium, geometric
// optics without refraction (Duysens 1956, Biochim Biophys Acta 19:1; the sphere's absorption efficiency
// Q = 1 - 2 (1 - (1 + x) e^-x) / x^2, van de Hulst 1957 Sec. 14.21): C_s = 3 Q / (2 x), x = 2 mu r; 1 at r = 0,
// 1 - 3x/8 + O(x^2) for small x, 3 / (2x) for large x.
double sphere_packaging_factor(double mu_per_cm, double radius_um);

}  // namespace skinspec
