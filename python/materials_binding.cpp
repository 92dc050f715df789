// skinspec.Material and the preset and field listings (docs/PYTHON.md "Materials"). Reading and setting a field
// go through the same descriptor tables and checks as `--set` (materials/material_file.hpp).
#include <nlohmann/json.hpp>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "materials/material_fields.hpp"
#include "python/bindings.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::python {
namespace {

// A Python value as the TOML text `--set` takes (a string is quoted, so "true" stays a string).
std::string toml_text(const py::handle& value, const std::string& key) {
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::str>(value)) return nlohmann::json(value.cast<std::string>()).dump();
    if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
        (py::hasattr(value, "__float__") && !py::hasattr(value, "__len__"))) {
        return format_number(value.cast<double>());
    }
    if (py::isinstance<py::sequence>(value) || py::hasattr(value, "__array__")) {
        const auto items = py::module_::import("numpy").attr("asarray")(value).attr("tolist")();
        if (!py::isinstance<py::list>(items)) return toml_text(items, key);
        std::string out = "[";
        for (const auto& item : items) {
            if (py::isinstance<py::list>(item)) throw InputError("material['" + key + "']: expected a value or a 1-D list, got a nested list");
            out += (out.size() > 1 ? ", " : "") + toml_text(item, key);
        }
        return out + "]";
    }
    throw InputError("material['" + key + "']: cannot set a " + py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>() +
                     " (expected a number, true/false, a string or a list)");
}

py::object python_value(const FieldValue& value) {
    return std::visit([](const auto& v) -> py::object { return py::cast(v); }, value);
}

void set_fields(PyMaterial& m, const std::vector<std::pair<std::string, std::string>>& fields) {
    std::vector<MaterialOverride> overrides;
    for (const auto& [key, text] : fields) overrides.push_back({key, text, "set"});
    m.material = with_overrides(m.material, overrides);
    m.overrides.insert(m.overrides.end(), overrides.begin(), overrides.end());
}

// The material as its labels should read once fields were set: NAME_changed, its description saying what changed
// (materials/material_file.hpp relabelled, as `materials save --set` labels a changed copy).
Material labelled(const PyMaterial& m) {
    if (m.overrides.empty()) return m.material;
    return relabelled(m.material, material_name(m.material) + "_changed", m.overrides);
}

std::string repr(const PyMaterial& m) {
    std::string parts;
    if (const auto* stack = std::get_if<LayerStack>(&m.material)) {
        for (const auto& l : stack->layers) parts += (parts.empty() ? "" : ", ") + l.name;
        parts = "layered: " + parts;
    } else {
        for (const auto& b : std::get<HomogeneousMaterial>(m.material).bands) parts += (parts.empty() ? "" : ", ") + b;
        parts = "homogeneous, bands " + parts;
    }
    return "<skinspec.Material '" + material_name(labelled(m)) + "' (" + parts + ")" +
           (m.overrides.empty() ? std::string() : ", " + std::to_string(m.overrides.size()) + " field(s) set") + ">";
}

}  // namespace

void bind_materials(py::module_& m) {
    py::class_<PyMaterial>(m, "Material", R"doc(A skin material: a preset or TOML file, its fields readable and settable.

    Material("biospec-moderately") loads a preset (see skinspec.presets()), Material("my.toml") a file.
    m["epidermis.melanosome_fraction"] reads a field as `skinspec materials keys` names it (a LAYER suffix such
    as "dermis" reads the layers it addresses when they agree); m[key] = value sets it with the same checks as
    --set (skinspec.InputError naming the field, the value and the range; the material is unchanged then).
    The fields set since loading are recorded in the provenance of every result computed from it.)doc")
        .def(py::init([](const py::object& name_or_file) { return material_argument(name_or_file, "Material"); }), py::arg("name_or_file"))
        .def_static(
            "from_toml", [](const std::string& text, const std::string& source) { return PyMaterial{parse_material(text, source), {}}; },
            py::arg("text"), py::arg("source") = "<string>", "A material from TOML text (as Material.to_toml() writes it).")
        .def("__getitem__", [](const PyMaterial& self, const std::string& key) { return python_value(material_field(self.material, key)); })
        .def("__setitem__",
             [](PyMaterial& self, const std::string& key, const py::handle& value) { set_fields(self, {{key, toml_text(value, key)}}); })
        .def(
            "update",
            [](PyMaterial& self, const py::dict& fields) {
                std::vector<std::pair<std::string, std::string>> texts;
                for (const auto& [k, v] : fields) texts.emplace_back(k.cast<std::string>(), toml_text(v, k.cast<std::string>()));
                set_fields(self, texts);
            },
            py::arg("fields"), "Sets several fields at once, checked together (all or none).")
        .def("__contains__",
             [](const PyMaterial& self, const std::string& key) {
                 try {
                     material_field(self.material, key);
                     return true;
                 } catch (const InputError&) {
                     return false;
                 }
             })
        .def("keys", [](const PyMaterial& self) { return material_keys(self.material); }, "Every field the material holds, in file order.")
        .def("__iter__", [](const PyMaterial& self) { return py::iter(py::cast(material_keys(self.material))); })
        .def("__len__", [](const PyMaterial& self) { return material_keys(self.material).size(); })
        .def("to_dict",
             [](const PyMaterial& self) {
                 py::dict out;
                 for (const auto& key : material_keys(self.material)) out[py::str(key)] = python_value(material_field(self.material, key));
                 return out;
             })
        .def_property_readonly("name", [](const PyMaterial& self) { return material_name(labelled(self)); })
        .def_property_readonly("description", [](const PyMaterial& self) { return material_description(labelled(self)); })
        .def_property_readonly("kind",
                               [](const PyMaterial& self) { return std::holds_alternative<LayerStack>(self.material) ? "layered" : "homogeneous"; })
        .def_property_readonly("layers",
                               [](const PyMaterial& self) {
                                   std::vector<std::string> names;
                                   if (const auto* s = std::get_if<LayerStack>(&self.material)) {
                                       for (const auto& l : s->layers) names.push_back(l.name);
                                   }
                                   return names;
                               })
        .def_property_readonly("bands",
                               [](const PyMaterial& self) {
                                   const auto* h = std::get_if<HomogeneousMaterial>(&self.material);
                                   return h ? h->bands : std::vector<std::string>{};
                               })
        .def_property_readonly("overrides",
                               [](const PyMaterial& self) {
                                   std::vector<std::pair<std::string, std::string>> out;
                                   for (const auto& o : self.overrides) out.emplace_back(o.key, o.value);
                                   return out;
                               },
                               "The (field, TOML value) pairs set since loading, in order.")
        .def("to_toml", [](const PyMaterial& self) { return to_toml(labelled(self)); })
        .def(
            "save", [](const PyMaterial& self, const std::filesystem::path& file, bool overwrite) { write_material(labelled(self), file, overwrite); },
            py::arg("file"), py::kw_only(), py::arg("overwrite") = false,
            "Writes the material as TOML; an existing file is replaced only with overwrite=True.")
        .def("copy", [](const PyMaterial& self) { return self; })
        .def("__copy__", [](const PyMaterial& self) { return self; })
        .def("__deepcopy__", [](const PyMaterial& self, const py::dict&) { return self; })
        .def("__eq__", [](const PyMaterial& a, const PyMaterial& b) { return labelled(a) == labelled(b); })
        .def("__repr__", &repr)
        .def(py::pickle(
            [](const PyMaterial& self) {
                std::vector<std::pair<std::string, std::string>> overrides;
                for (const auto& o : self.overrides) overrides.emplace_back(o.key, o.value);
                return py::make_tuple(to_toml(self.material), overrides);
            },
            [](const py::tuple& state) {
                PyMaterial out{parse_material(state[0].cast<std::string>(), "pickled material"), {}};
                for (const auto& [key, value] : state[1].cast<std::vector<std::pair<std::string, std::string>>>()) {
                    out.overrides.push_back({key, value, "set"});
                }
                return out;
            }));

    m.def(
        "presets",
        [] {
            std::vector<std::string> names;
            for (const auto& f : preset_files()) names.push_back(f.stem().string());
            return names;
        },
        "The material presets (names for skinspec.Material).");
    m.def(
        "fields",
        [] {
            py::list rows;
            for (const auto& r : material_field_rows()) {
                rows.append(py::dict(py::arg("key") = r.key, py::arg("unit") = r.unit, py::arg("allowed") = r.allowed, py::arg("doc") = r.doc));
            }
            return rows;
        },
        "Every material field (as `skinspec materials keys` lists them): key, unit, allowed range or names, meaning.");
    m.def("absorption_only_fields", &absorption_only_fields, "The fields sweeps replay from one set of traced paths.");
    m.def("data_directory", &data_directory, "The folder skinspec reads its tables from.");
    m.def("_set_default_data_directory", &set_default_data_directory);
}

}  // namespace skinspec::python
