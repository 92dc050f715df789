// skinspec.fit_image (docs/PYTHON.md "fit_image", docs/FIT_IMAGE.md): per-pixel maps of a skin albedo image through
// the skin model, computed by the library call `skinspec fit-image` makes, returned as numpy arrays with the
// command's --json summary.
#include <pybind11/stl.h>

#include "appearance/lut_export.hpp"
#include "inverse/image_fit/skin_image_fit.hpp"
#include "python/bindings.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::python {
namespace {

// An image file, or an array (height, width, channels) of linear values ((height, width) for one channel).
SkinImage image_argument(const py::object& image, const SkinImageRequest& request) {
    if (is_path(image)) return read_skin_image(path_argument(image, "image"), request);
    check_skin_image_request(request);
    const auto a = finite_array(image, "image");
    const std::size_t k = request.bands ? request.bands->names.size() : 3;
    const auto channels = a.ndim() == 3 ? static_cast<std::size_t>(a.shape(2)) : 1;
    if (!(a.ndim() == 3 || a.ndim() == 2) || channels != k) {
        throw InputError("image: expected an array (height, width, " + std::to_string(k) + ") of " +
                         (request.bands ? "band values" : "linear RGB values in " + request.space) + " or an image file");
    }
    SkinImage out{static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), {}};
    out.values.reserve(static_cast<std::size_t>(a.size()));
    for (py::ssize_t i = 0; i < a.size(); ++i) out.values.push_back(static_cast<float>(a.data()[i]));
    return out;
}

py::object fit_image(const py::object& image, const std::string& material, const std::string& melanin, const std::string& blood,
                     const py::object& set, const py::object& space, const py::object& bands, const py::object& white, const py::object& noise,
                     double gamut_sigma, const py::object& edit, const std::string& solver, const py::object& geometry, double delta_e,
                     const std::string& illuminant, const std::string& observer, const py::object& seed, const py::object& max_rays,
                     const py::object& threads, const py::object& progress, const py::kwargs& switches) {
    SkinImageRequest request;
    request.table = swatch_request_argument(material, set, delta_e, illuminant, observer, solver, seed, max_rays,
                                            geometry.is_none() ? std::string(to_string(image_geometry)) : geometry.cast<std::string>(), switches);
    const auto u = lut_axis(lut_melanin_field, melanin, "melanin");
    const auto v = lut_axis(lut_blood_field, blood, "blood");
    request.table.sweeps = {u, v};
    if (bands.is_none()) request.space = ColorManagement::builtin().canonical_space(space.is_none() ? "Linear Rec.709" : space.cast<std::string>(), "space");
    else request.bands = read_band_sensitivities(path_argument(bands, "bands"));
    request.white = finite_vector(white, "white");
    if (!noise.is_none()) request.fit.noise = one_number(noise, "noise");
    request.fit.gamut_sigma = gamut_sigma;
    if (!edit.is_none()) {
        for (const auto& e : name_list(edit, "edit")) request.edits.push_back(parse_field_edit(e, u.field, v.field));
    }
    const auto pixels = image_argument(image, request);
    // An image file skinspec wrote states its colour space and geometry (stated_image_settings): taken unless given (a
    // stated space is a float image's, whose values are read as they are).
    if (bands.is_none() && space.is_none() && pixels.stated.space) request.space = *pixels.stated.space;
    if (geometry.is_none() && pixels.stated.geometry) request.table.geometry = *pixels.stated.geometry;
    const ThreadLimit limit(threads);
    SkinImageFit result;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            auto r = request;
            r.table.cancel = &cancel;
            r.fit.cancel = &cancel;
            r.table.on_progress = [&report](std::size_t done, std::size_t total) { report(Progress{0, 0, done, total}); };
            r.fit.on_progress = [&report](std::size_t done, std::size_t total) { report(Progress{0, 0, done, total}); };
            result = fit_skin_image(r, pixels);
        },
        progress);
    py::dict out = json_object(skin_image_summary_json(result, request, is_path(image) ? path_argument(image, "image").string() : "array"));
    const auto maps = skin_image_maps(result);
    const auto h = static_cast<py::ssize_t>(maps.height), w = static_cast<py::ssize_t>(maps.width);
    py::dict planes;
    for (std::size_t c = 0; c < maps.channel_names.size(); ++c) {
        std::vector<double> plane;
        plane.reserve(static_cast<std::size_t>(h * w));
        for (std::size_t p = 0; p < static_cast<std::size_t>(h * w); ++p) plane.push_back(maps.values[p * maps.channel_names.size() + c]);
        planes[py::str(maps.channel_names[c])] = to_array(plane, {h, w});
    }
    out["maps"] = planes;
    if (result.edited) {
        const auto k = static_cast<py::ssize_t>(result.lut->channel_count());
        out["edited"] = to_array(std::vector<double>(result.edited->values.begin(), result.edited->values.end()), {h, w, k});
    }
    out["warnings"] = summarise_warnings(result.warnings);
    return out;
}

}  // namespace

void bind_image_fit(py::module_& m) {
    m.def("fit_image", &fit_image, R"doc(Per-pixel melanosome and blood maps of a skin albedo image, as `skinspec fit-image` fits them.

    image: an image file (a linear OpenEXR in `space`, or an sRGB-encoded PNG/JPEG/TIFF), or an array (height, width, 3)
    of linear RGB in `space` (with bands: (height, width, bands) of band values); material: a preset name or .toml
    path; melanin, blood: the model's table, "FIRST:LAST:STEPS[:log]" of epidermis.melanosome_fraction and
    dermis.blood_fraction; set: {field: value} overrides; bands: a CSV of band sensitivities (wavelength_nm,BAND,...)
    for a multispectral image; white: the image value of a perfect white diffuser (one number, or one per channel: a white balance); noise: the standard deviation of each
    channel value (None: estimated from the residuals); gamut_sigma: a residual above this many noise sigmas is outside
    the model's gamut; edit: "FIELD=*SCALE" or "FIELD=VALUE" (or a list): the image re-rendered with the fitted fields
    changed, returned as "edited" (fitted pixels whose edited fields leave the table unchanged, counted in
    "edit"); mode (the solver, as --mode; default "biospec-adding-doubling"), geometry and space (default None: what an image
    file skinspec wrote states, else "sce" and "Linear Rec.709"), delta_e,
    illuminant, observer, seed, max_rays, threads, progress (called with the table's nodes, then the image's rows) and
    solver switches as skinspec.swatch takes them. Returns the command's --json
    summary with "maps": (height, width) arrays named as the maps' OpenEXR channels (both fields, "FIELD.stderr",
    "residual", "status": 0 fitted, 1 outside the model's gamut, 2 on the table's edge, 3 invalid, 4 not fitted).)doc",
          py::arg("image"), py::kw_only(), py::arg("material") = "biospec-moderately", py::arg("melanin") = "0.005:0.45:24:log",
          py::arg("blood") = "0.001:0.1:16:log", py::arg("set") = py::none(), py::arg("space") = py::none(), py::arg("bands") = py::none(),
          py::arg("white") = 1.0, py::arg("noise") = py::none(), py::arg("gamut_sigma") = 4.0, py::arg("edit") = py::none(),
          py::arg("mode") = "biospec-adding-doubling", py::arg("geometry") = py::none(), py::arg("delta_e") = 0.5, py::arg("illuminant") = "D65",
          py::arg("observer") = "2", py::arg("seed") = py::none(), py::arg("max_rays") = py::none(), py::arg("threads") = py::none(),
          py::arg("progress") = py::none());
}

}  // namespace skinspec::python
