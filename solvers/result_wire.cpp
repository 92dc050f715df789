#include "solvers/result_wire.hpp"

#include <cstring>
#include <type_traits>

#include "spectral/input_error.hpp"
#include "transport/result_quantities.hpp"

namespace skinspec {
namespace {

// One list of fields for both directions: transfer(archive, result) hands every field to the archive, the
// Writer appending it, the Reader filling it.
template <class Archive, class Result>
void transfer(Archive& a, Result& r) {
    a(r.model), a(r.material), a(r.settings), a(r.model_settings), a(r.layer_names), a(r.angular_bin_edges_deg);
    a(r.quantities.reflectance), a(r.quantities.transmittance), a(r.quantities.absorptance), a(r.quantities.angular);
    a(r.wavelengths), a(r.partial), a(r.has_uncertainty), a(r.bands), a(r.warnings), a(r.stated_error);
    a(r.provenance.solver), a(r.provenance.material_toml), a(r.provenance.overrides), a(r.provenance.varied), a(r.provenance.version);
}
template <class Archive, class Wavelength>
void transfer_wavelength(Archive& a, Wavelength& x) {
    a(x.wavelength_nm);
    for (const auto& q : result_quantities()) std::visit([&](auto member) { a(x.*member); }, q.member);  // every quantity of the table
    a(x.rays), a(x.truncated_rays), a(x.converged);
}
template <class Archive, class Warning>
void transfer_warning(Archive& a, Warning& w) {
    a(w.kind), a(w.subject), a(w.at), a(w.value);
}

class Writer {
public:
    template <class T>
        requires std::is_arithmetic_v<T>
    Writer& operator()(T v) {
        out_.append(reinterpret_cast<const char*>(&v), sizeof v);
        return *this;
    }
    Writer& operator()(const std::string& s) {
        (*this)(static_cast<std::uint64_t>(s.size()));
        out_ += s;
        return *this;
    }
    Writer& operator()(const Estimate& e) { return (*this)(e.value)(e.stderr); }
    Writer& operator()(const ResultWarning& w) {
        transfer_warning(*this, w);
        return *this;
    }
    Writer& operator()(const WavelengthResult& x) {
        transfer_wavelength(*this, x);
        return *this;
    }
    // A setting as its type index, then the value: integers stay integers, booleans booleans.
    Writer& operator()(const SettingValue& v) {
        (*this)(static_cast<std::uint8_t>(v.index()));
        std::visit([&](const auto& x) { (*this)(x); }, v);
        return *this;
    }
    // A material text; unset (provenance not yet recorded) travels as empty, which no material writes.
    Writer& operator()(const StatedError& e) { return (*this)(e.R)(e.meaning)(e.delta_e2000); }
    template <class T>
    Writer& operator()(const std::optional<T>& v) {
        (*this)(static_cast<std::uint8_t>(v.has_value()));
        if (v) (*this)(*v);
        return *this;
    }
    Writer& operator()(const std::shared_ptr<const std::string>& s) { return (*this)(s ? *s : std::string()); }
    Writer& operator()(const SweptValues& v) { return (*this)(v.fields ? *v.fields : std::vector<std::string>())(v.values); }
    Writer& operator()(const std::shared_ptr<const ResultSettings>& s) {
        (*this)(static_cast<std::uint8_t>(s != nullptr));
        if (s) (*this)(*s);
        return *this;
    }
    template <class A, class B>
    Writer& operator()(const std::pair<A, B>& p) {
        return (*this)(p.first)(p.second);
    }
    template <class K, class V>
    Writer& operator()(const std::map<K, V>& m) {
        (*this)(static_cast<std::uint64_t>(m.size()));
        for (const auto& [k, v] : m) (*this)(k)(v);
        return *this;
    }
    template <class T>
    Writer& operator()(const std::vector<T>& v) {
        (*this)(static_cast<std::uint64_t>(v.size()));
        if constexpr (std::is_arithmetic_v<T>) {
            if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
        } else {
            for (const auto& x : v) (*this)(x);
        }
        return *this;
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
    Reader& operator()(T& v) {
        need(sizeof v);
        std::memcpy(&v, bytes_.data() + at_, sizeof v);
        at_ += sizeof v;
        return *this;
    }
    Reader& operator()(std::string& s) {
        const auto n = count();
        need(n);
        s.assign(bytes_.data() + at_, n);
        at_ += n;
        return *this;
    }
    Reader& operator()(Estimate& e) { return (*this)(e.value)(e.stderr); }
    Reader& operator()(ResultWarning& w) {
        transfer_warning(*this, w);
        return *this;
    }
    Reader& operator()(WavelengthResult& x) {
        transfer_wavelength(*this, x);
        return *this;
    }
    Reader& operator()(SettingValue& v) {
        std::uint8_t kind = 0;
        (*this)(kind);
        const auto read = [&]<class T>(T value) {
            (*this)(value);
            v = value;
        };
        switch (kind) {
            case 0: read(false); break;
            case 1: read(std::uint64_t{0}); break;
            case 2: read(0.0); break;
            case 3: read(std::string()); break;
            default: throw InputError("result bytes: unknown setting type " + std::to_string(kind));
        }
        return *this;
    }
    Reader& operator()(StatedError& e) { return (*this)(e.R)(e.meaning)(e.delta_e2000); }
    template <class T>
    Reader& operator()(std::optional<T>& v) {
        std::uint8_t has = 0;
        (*this)(has);
        if (has > 1) throw InputError("result bytes: an optional flag of " + std::to_string(has));
        v.reset();
        if (has) (*this)(v.emplace());
        return *this;
    }
    Reader& operator()(std::shared_ptr<const std::string>& s) {
        std::string text;
        (*this)(text);
        s = text.empty() ? nullptr : std::make_shared<const std::string>(std::move(text));
        return *this;
    }
    Reader& operator()(SweptValues& v) {
        std::vector<std::string> fields;
        (*this)(fields)(v.values);
        if (fields.size() != v.values.size()) throw InputError("result bytes: " + std::to_string(fields.size()) + " swept fields with " + std::to_string(v.values.size()) + " values");
        v.fields = fields.empty() ? nullptr : std::make_shared<const std::vector<std::string>>(std::move(fields));
        return *this;
    }
    Reader& operator()(std::shared_ptr<const ResultSettings>& s) {
        std::optional<ResultSettings> settings;
        (*this)(settings);
        s = settings ? std::make_shared<const ResultSettings>(std::move(*settings)) : nullptr;
        return *this;
    }
    template <class A, class B>
    Reader& operator()(std::pair<A, B>& p) {
        return (*this)(p.first)(p.second);
    }
    template <class K, class V>
    Reader& operator()(std::map<K, V>& m) {
        for (auto n = count(); n > 0; --n) {
            K key;
            (*this)(key);
            (*this)(m[key]);
        }
        return *this;
    }
    template <class T>
    Reader& operator()(std::vector<T>& v) {
        const auto n = count();
        if constexpr (std::is_arithmetic_v<T>) {
            need(n * sizeof(T));
            v.resize(n);
            if (n > 0) std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
            at_ += n * sizeof(T);
        } else {
            v.resize(n);
            for (auto& x : v) (*this)(x);
        }
        return *this;
    }
    // A length: at most the bytes there are (a corrupted one fails here, before any allocation).
    std::uint64_t count() {
        std::uint64_t n = 0;
        (*this)(n);
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

}  // namespace

std::string results_to_bytes(const std::vector<SpectralResult>& results) {
    Writer w;
    w(static_cast<std::uint64_t>(results.size()));
    for (const auto& r : results) transfer(w, r);
    return w.take();
}

std::vector<SpectralResult> results_from_bytes(const std::string& bytes) {
    Reader in(bytes);
    std::vector<SpectralResult> out(in.count());
    for (auto& r : out) transfer(in, r);
    if (!in.done()) throw InputError("result bytes: " + std::to_string(bytes.size()) + " bytes hold more than the results");
    return out;
}

}  // namespace skinspec
