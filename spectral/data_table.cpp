#include "spectral/data_table.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

DataTable DataTable::read(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw InputError(file.string() + ": cannot open data table");
    DataTable table;
    table.file_ = file;
    const auto where = [&](std::size_t line) { return file.string() + ":" + std::to_string(line) + ": "; };

    std::string line;
    std::size_t line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        const auto text = trim(line);
        if (text.empty()) continue;
        if (text.front() == '#') {
            const auto body = trim(text.substr(1));
            const auto colon = body.find(':');
            if (colon == std::string_view::npos) continue;
            const std::string key(trim(body.substr(0, colon)));
            const std::string value(trim(body.substr(colon + 1)));
            auto& slot = table.metadata_[key];
            slot = slot.empty() ? value : slot + "\n" + value;
            continue;
        }
        const auto fields = split_fields(text);
        if (table.column_names_.empty()) {
            if (table.metadata("skinspec-table") != "1") {
                throw InputError(where(line_number) + "unsupported skinspec-table version '" +
                                 table.metadata("skinspec-table") + "' (allowed: 1)");
            }
            for (const auto f : fields) table.column_names_.emplace_back(f);
            if (table.column_names_.front() != "wavelength_nm") {
                throw InputError(where(line_number) + "first column is '" + table.column_names_.front() +
                                 "' (allowed: wavelength_nm)");
            }
            table.columns_.resize(fields.size());
            continue;
        }
        if (fields.size() != table.column_names_.size()) {
            throw InputError(where(line_number) + std::to_string(fields.size()) + " fields (allowed: " +
                             std::to_string(table.column_names_.size()) + ", one per column)");
        }
        for (std::size_t c = 0; c < fields.size(); ++c) {
            const auto value = parse_double(fields[c]);
            if (!value || !std::isfinite(*value)) {
                throw InputError(where(line_number) + "field '" + table.column_names_[c] + "' = '" +
                                 std::string(fields[c]) + "' is not a finite number");
            }
            table.columns_[c].push_back(*value);
        }
    }
    if (table.column_names_.empty() || table.columns_.front().size() < 2) {
        throw InputError(file.string() + ": no data rows (allowed: a column line and at least 2 rows)");
    }
    table.outside_ = parse_out_of_range_policy(table.metadata("outside_domain"), file.string() + ": outside_domain");
    return table;
}

bool DataTable::has_metadata(std::string_view key) const { return metadata_.find(key) != metadata_.end(); }

const std::string& DataTable::metadata(std::string_view key) const {
    const auto it = metadata_.find(key);
    if (it == metadata_.end()) {
        throw InputError(file_.string() + ": header line '# " + std::string(key) + ": ...' is missing");
    }
    return it->second;
}

std::span<const double> DataTable::column(std::string_view name) const {
    const auto it = std::find(column_names_.begin(), column_names_.end(), name);
    if (it == column_names_.end()) {
        throw InputError(file_.string() + ": no column '" + std::string(name) + "'");
    }
    return columns_[static_cast<std::size_t>(it - column_names_.begin())];
}

TabulatedSpectrum DataTable::spectrum(std::string_view column_name, std::string spectrum_name) const {
    const auto wavelengths = column("wavelength_nm");
    const auto values = column(column_name);
    return TabulatedSpectrum(std::move(spectrum_name), {wavelengths.begin(), wavelengths.end()},
                             {values.begin(), values.end()}, outside_);
}

}  // namespace skinspec
