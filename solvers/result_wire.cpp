#include "solvers/result_wire.hpp"

#include <cstring>
#include <type_traits>

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

class Writer {
public:
    template <class T>
        requires std::is_arithmetic_v<T>
    void put(T v) {
        out_.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void put(const std::string& s) {
        put<std::uint64_t>(s.size());
        out_ += s;
    }
    void put(const Estimate& e) {
        put(e.value);
        put(e.stderr);
    }
    void put(const ResultWarning& w) {
        put(w.kind);
        put(w.subject);
        put(w.at);
        put(w.value);
    }
    template <class A, class B>
    void put(const std::pair<A, B>& p) {
        put(p.first);
        put(p.second);
    }
    template <class T>
    void put(const std::vector<T>& v) {
        put<std::uint64_t>(v.size());
        if constexpr (std::is_arithmetic_v<T>) {
            out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
        } else {
            for (const auto& x : v) put(x);
        }
    }
    std::string take() { return std::move(out_); }

private:
    std::string out_;
};

class Reader {
public:
    explicit Reader(const std::string& bytes) : bytes_(bytes) {}
    template <class T>
        requires std::is_arithmetic_v<T>
    void get(T& v) {
        need(sizeof v);
        std::memcpy(&v, bytes_.data() + at_, sizeof v);
        at_ += sizeof v;
    }
    void get(std::string& s) {
        const auto n = count();
        need(n);
        s.assign(bytes_.data() + at_, n);
        at_ += n;
    }
    void get(Estimate& e) {
        get(e.value);
        get(e.stderr);
    }
    void get(ResultWarning& w) {
        get(w.kind);
        get(w.subject);
        get(w.at);
        get(w.value);
    }
    template <class A, class B>
    void get(std::pair<A, B>& p) {
        get(p.first);
        get(p.second);
    }
    template <class T>
    void get(std::vector<T>& v) {
        const auto n = count();
        if constexpr (std::is_arithmetic_v<T>) {
            need(n * sizeof(T));
            v.resize(n);
            std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
            at_ += n * sizeof(T);
        } else {
            v.resize(n);
            for (auto& x : v) get(x);
        }
    }
    std::uint64_t count() {
        std::uint64_t n = 0;
        get(n);
        if (n > bytes_.size()) throw InputError("result bytes: a length of " + std::to_string(n) + " in " + std::to_string(bytes_.size()) + " bytes");
        return n;
    }
    bool done() const { return at_ == bytes_.size(); }

private:
    void need(std::size_t n) const {
        if (n > bytes_.size() - at_) throw InputError("result bytes: truncated at byte " + std::to_string(at_));
    }
    const std::string& bytes_;
    std::size_t at_ = 0;
};

void put_setting(Writer& w, const SettingValue& v) {
    w.put<std::uint8_t>(static_cast<std::uint8_t>(v.index()));
    std::visit([&](const auto& x) { w.put(x); }, v);
}

SettingValue get_setting(Reader& r) {
    std::uint8_t kind = 0;
    r.get(kind);
    const auto read = [&]<class T>(T value) -> SettingValue {
        r.get(value);
        return value;
    };
    switch (kind) {
        case 0: return read(false);
        case 1: return read(std::uint64_t{0});
        case 2: return read(0.0);
        case 3: return read(std::string());
        default: throw InputError("result bytes: unknown setting type " + std::to_string(kind));
    }
}

void put_quantities(Writer& w, const Quantities& q) {
    for (const bool b : {q.reflectance, q.transmittance, q.absorptance, q.angular}) w.put(b);
}

}  // namespace

std::string results_to_bytes(const std::vector<SpectralResult>& results) {
    Writer w;
    w.put<std::uint64_t>(results.size());
    for (const auto& r : results) {
        w.put(r.model);
        w.put(r.material);
        w.put<std::uint64_t>(r.settings.size());
        for (const auto& [k, v] : r.settings) {
            w.put(k);
            put_setting(w, v);
        }
        w.put(r.layer_names);
        w.put(r.angular_bin_edges_deg);
        put_quantities(w, r.quantities);
        w.put<std::uint64_t>(r.wavelengths.size());
        for (const auto& x : r.wavelengths) {
            w.put(x.wavelength_nm);
            w.put(x.reflectance);
            w.put(x.specular_reflectance);
            w.put(x.transmittance);
            w.put(x.absorptance_layers);
            w.put(x.absorptance_surface);
            w.put(x.brdf_per_sr);
            w.put(x.btdf_per_sr);
            w.put(x.rays);
            w.put(x.truncated_rays);
            w.put(x.converged);
        }
        w.put(r.partial);
        w.put(r.has_uncertainty);
        w.put(r.bands);
        w.put(r.warnings);
        w.put(r.provenance.solver);
        w.put(r.provenance.material_toml);
        w.put(r.provenance.overrides);
        w.put(r.provenance.varied);
        w.put(r.provenance.version);
    }
    return w.take();
}

std::vector<SpectralResult> results_from_bytes(const std::string& bytes) {
    Reader in(bytes);
    std::vector<SpectralResult> out(in.count());
    for (auto& r : out) {
        in.get(r.model);
        in.get(r.material);
        for (auto n = in.count(); n > 0; --n) {
            std::string key;
            in.get(key);
            r.settings[key] = get_setting(in);
        }
        in.get(r.layer_names);
        in.get(r.angular_bin_edges_deg);
        in.get(r.quantities.reflectance);
        in.get(r.quantities.transmittance);
        in.get(r.quantities.absorptance);
        in.get(r.quantities.angular);
        r.wavelengths.resize(in.count());
        for (auto& x : r.wavelengths) {
            in.get(x.wavelength_nm);
            in.get(x.reflectance);
            in.get(x.specular_reflectance);
            in.get(x.transmittance);
            in.get(x.absorptance_layers);
            in.get(x.absorptance_surface);
            in.get(x.brdf_per_sr);
            in.get(x.btdf_per_sr);
            in.get(x.rays);
            in.get(x.truncated_rays);
            in.get(x.converged);
        }
        in.get(r.partial);
        in.get(r.has_uncertainty);
        in.get(r.bands);
        in.get(r.warnings);
        in.get(r.provenance.solver);
        in.get(r.provenance.material_toml);
        in.get(r.provenance.overrides);
        in.get(r.provenance.varied);
        in.get(r.provenance.version);
    }
    if (!in.done()) throw InputError("result bytes: " + std::to_string(bytes.size()) + " bytes hold more than the results");
    return out;
}

}  // namespace skinspec
